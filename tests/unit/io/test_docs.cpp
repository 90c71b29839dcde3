// SPDX-License-Identifier: BSD-3-Clause
// The documentation against the code it describes, so that neither drifts:
//  - docs/case_file.md documents exactly the keys the case reader accepts
//    (declared_case_keys(), built from the same lists read_case checks);
//  - README.md stays a front door (at most 200 lines);
//  - README.md and docs/ cite nothing a clone of the repository lacks
//    (no DESIGN.md, no ../shared) and every relative link they hold exists.
// The commands the documents show are run by scripts/check_doc_commands.sh.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "io/case_file.hpp"

namespace {

namespace fs = std::filesystem;
const fs::path kRoot = IGAC_SOURCE_DIR;

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  EXPECT_TRUE(in.good()) << p;
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The keys docs/case_file.md documents: the first cell of a table row, when
// it is one backticked key ("| `mesh.degree` | integer | ...").
std::set<std::string> documented_keys(const std::string& text) {
  std::set<std::string> keys;
  const std::regex row(R"(^\| `([A-Za-z0-9_.*]+)` \|)");
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_search(line, m, row)) keys.insert(m[1]);
  }
  return keys;
}

std::vector<fs::path> documents() {
  std::vector<fs::path> out{kRoot / "README.md"};
  for (const auto& e : fs::directory_iterator(kRoot / "docs"))
    if (e.path().extension() == ".md") out.push_back(e.path());
  return out;
}

}  // namespace

TEST(Docs, CaseFileReferenceDocumentsEveryDeclaredKey) {
  const auto declared = igac::declared_case_keys();
  ASSERT_GT(declared.size(), 40u);  // the fixed tables alone have more: the list is not empty by mistake
  const auto documented = documented_keys(read_text(kRoot / "docs/case_file.md"));
  for (const auto& k : declared) EXPECT_TRUE(documented.count(k)) << "docs/case_file.md does not document `" << k << "`";
}

TEST(Docs, CaseFileReferenceDocumentsNoKeyTheReaderRefuses) {
  const auto declared_list = igac::declared_case_keys();
  const std::set<std::string> declared(declared_list.begin(), declared_list.end());
  for (const auto& k : documented_keys(read_text(kRoot / "docs/case_file.md")))
    EXPECT_TRUE(declared.count(k)) << "docs/case_file.md documents `" << k << "`, which the case reader refuses";
}

TEST(Docs, DeclaredKeysIncludeTheRegistries) {
  // Keys that come from the shape, law and obstacle registries, not from
  // io/case_file.cpp's own lists.
  const auto d = igac::declared_case_keys();
  const std::set<std::string> declared(d.begin(), d.end());
  for (const char* k : {"geometry.radius", "geometry.size", "material.E", "material.C10", "contact.obstacle.normal",
                        "contact.obstacle.axis", "mesh.grading.coarse", "faces.*"})
    EXPECT_TRUE(declared.count(k)) << k;
}

TEST(Docs, ReadmeIsAFrontDoorOfAtMost200Lines) {
  const std::string text = read_text(kRoot / "README.md");
  const auto lines = std::count(text.begin(), text.end(), '\n');
  EXPECT_LE(lines, 200);
}

TEST(Docs, DocumentsCiteOnlyWhatTheRepositoryHolds) {
  const std::regex link(R"(\]\(([^)#:]+)(#[^)]*)?\))");  // [text](relative/path) — no URL scheme
  for (const auto& doc : documents()) {
    const std::string text = read_text(doc);
    EXPECT_EQ(text.find("DESIGN.md"), std::string::npos) << doc << " cites DESIGN.md, which is not in the repository";
    EXPECT_EQ(text.find("../shared"), std::string::npos) << doc << " cites a path outside the repository";
    for (std::sregex_iterator it(text.begin(), text.end(), link), end; it != end; ++it) {
      const fs::path target = doc.parent_path() / (*it)[1].str();
      EXPECT_TRUE(fs::exists(target)) << doc << " links to " << (*it)[1] << ", which does not exist";
    }
  }
}
