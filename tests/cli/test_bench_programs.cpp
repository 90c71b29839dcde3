// SPDX-License-Identifier: BSD-3-Clause
// The bench programs (bench/*.cpp) print what their --csv file holds, the
// CSV header first (issue 25: a newcomer piping one into a file or a
// spreadsheet got rows without names; inf_sup printed prose).
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;

// Runs build/bench/PROGRAM ARGS --csv out.csv: stdout is the file's text.
void expect_stdout_is_the_csv(const std::string& program, const std::string& args, const std::string& first_column) {
  igac_test::TempDir tmp("bench");
  const fs::path exe = fs::path(IGAC_BINARY).parent_path() / "bench" / program;
  ASSERT_TRUE(fs::exists(exe)) << exe;
  const std::string cmd = "cd " + igac_test::quote(tmp.path().string()) + " && " + igac_test::quote(exe.string()) + " " +
                          args + " --csv out.csv 2>/dev/null";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buf[4096];
  for (size_t n; (n = fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, n);
  ASSERT_EQ(pclose(pipe), 0) << program << ": " << out;
  EXPECT_EQ(out.rfind(first_column + ",", 0), 0u) << program << " printed first: " << out;
  EXPECT_EQ(out, igac_test::read_file(tmp.path() / "out.csv")) << program;
  EXPECT_GE(std::count(out.begin(), out.end(), '\n'), 2) << program << ": a header and a row";
}

const std::string kSource = IGAC_SOURCE_DIR;

TEST(BenchPrograms, PrintTheirCsvHeaderFirst) {
  expect_stdout_is_the_csv("contact_vs_cholesky", igac_test::quote(kSource + "/cases/hertz2d.toml") + " 0 --repeat 1", "case");
  expect_stdout_is_the_csv("newton_vs_linear",
                           igac_test::quote(kSource + "/tests/data/curve_block_neohookean.toml") + " 0 --repeat 1", "case");
  expect_stdout_is_the_csv("inf_sup", "4", "degree");
  expect_stdout_is_the_csv("master_search", "4 --queries 10", "master_elements");
}

}  // namespace
