// SPDX-License-Identifier: BSD-3-Clause
// Which igac and which input a result came from: `igac --version`, and in
// summary.json the version and the case file's absolute path and FNV-1a
// hash (a changed case file, a changed hash).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;

TEST(Version, VersionFlagPrintsTheVersion) {
  igac_test::TempDir tmp("version");
  const auto o = igac_test::run_igac("--version", tmp.path());
  EXPECT_EQ(o.exit_code, 0);
  EXPECT_EQ(o.output, std::string("igac ") + IGAC_VERSION + "\n");
}

TEST(Version, SummaryNamesTheVersionAndTheInputWithItsHash) {
  igac_test::TempDir tmp("version_summary");
  const fs::path cases = fs::path(IGAC_SOURCE_DIR) / "cases";
  fs::copy_file(cases / "two_blocks.xml", tmp.path() / "two_blocks.xml");
  fs::copy_file(cases / "two_blocks.toml", tmp.path() / "case.toml");
  auto run = [&]() {
    const auto o = igac_test::run_igac("run case.toml --out result --quiet", tmp.path());
    EXPECT_EQ(o.exit_code, 0) << o.output;
    return nlohmann::json::parse(igac_test::read_file(tmp.path() / "result" / "summary.json"));
  };
  const auto first = run();
  EXPECT_EQ(first["igac_version"], IGAC_VERSION);
  EXPECT_EQ(first["input"]["path"], (tmp.path() / "case.toml").lexically_normal().string());
  const std::string hash = first["input"]["fnv1a64"];
  EXPECT_EQ(hash.size(), 16u);
  std::ofstream(tmp.path() / "case.toml", std::ios::app) << "# a comment changes the file, not the case\n";
  const auto second = run();
  EXPECT_NE(second["input"]["fnv1a64"], hash);
  EXPECT_EQ(second["contact"]["total_force"], first["contact"]["total_force"]);
}

}  // namespace
