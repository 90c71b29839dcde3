// SPDX-License-Identifier: BSD-3-Clause
// Inputs a new user brings that used to hang, overflow or write non-numbers:
// a geometry "file" that is a FIFO or a device (read forever, or until the
// memory ran out), a load of 1e308 (accepted, and the failed run wrote nan
// and inf into its CSV).  Each is one line and exit 2 now, with nothing
// written; and no CSV cell igac writes is ever "nan" or "inf".
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "io/json_out.hpp"
#include "tests/support/igac_process.hpp"

namespace {

using igac_test::Outcome;
using igac_test::quote;
using igac_test::run_igac;
using igac_test::TempDir;

constexpr int kBadInputExit = 2;  // docs/design.md, "Errors and exit codes"

// hertz2d.toml with its body read from `geometry`.
std::string case_with_geometry(const std::filesystem::path& dir, const std::string& geometry) {
  const std::string path = (dir / "case.toml").string();
  std::ofstream(path) << "[geometry]\nfile = \"" << geometry
                      << "\"\n[mesh]\ndegree = 2\nelements = [4, 4]\n[material]\nE = 1.0\nnu = 0.3\n"
                         "[[dirichlet]]\nfaces = [\"0:west\"]\ncomponent = \"x\"\n";
  return path;
}

void expect_one_line_rejection(const Outcome& o, const std::string& says) {
  EXPECT_EQ(o.exit_code, kBadInputExit) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  EXPECT_NE(o.output.find(says), std::string::npos) << o.output;
}

TEST(UserInputs, GeometryFileThatIsAFifoIsRefused) {
  TempDir tmp("inputs");
  const std::string fifo = (tmp.path() / "body.xml").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const Outcome o = run_igac("run " + quote(case_with_geometry(tmp.path(), fifo)) + " --out out", tmp.path());
  expect_one_line_rejection(o, "not a regular file");
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out"));
}

TEST(UserInputs, GeometryFileThatIsADeviceIsRefused) {
  TempDir tmp("inputs");
  const Outcome o = run_igac("run " + quote(case_with_geometry(tmp.path(), "/dev/zero")) + " --out out", tmp.path());
  expect_one_line_rejection(o, "not a regular file");
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out"));
}

TEST(UserInputs, LoadsBeyondTheRangeOfDoublesAreRefused) {
  const std::string hertz2d = std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml";
  std::ifstream in(hertz2d);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find("value = 0.003");
  ASSERT_NE(at, std::string::npos);
  for (const std::string load : {"1e308", "-1e101"}) {
    TempDir tmp("inputs");
    std::string changed = text;
    changed.replace(at, 13, "value = " + load);
    std::ofstream(tmp.path() / "case.toml") << changed;
    const Outcome o = run_igac("run case.toml --out out", tmp.path());
    expect_one_line_rejection(o, "[pressure] value");
    EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out")) << load;
  }
}

TEST(UserInputs, CsvCellsAreNeverNanOrInf) {
  EXPECT_EQ(igac::csv_number(std::numeric_limits<double>::quiet_NaN()), "");
  EXPECT_EQ(igac::csv_number(std::numeric_limits<double>::infinity()), "");
  EXPECT_EQ(igac::csv_number(-std::numeric_limits<double>::infinity()), "");
  EXPECT_EQ(igac::csv_number(0.1), "0.1");
  EXPECT_EQ(igac::csv_number(1.0 / 3.0), "0.3333333333");
}

}  // namespace
