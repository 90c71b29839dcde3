// SPDX-License-Identifier: BSD-3-Clause
// The bench programs (bench/*.cpp) print what their --csv file holds, the
// CSV header first (issue 25: a newcomer piping one into a file or a
// spreadsheet got rows without names; inf_sup printed prose).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;

// The output of the shell command CMD; its wait status in *status.
std::string command_output(const std::string& cmd, int* status) {
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  for (size_t n; pipe && (n = fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, n);
  *status = pipe ? pclose(pipe) : -1;
  return out;
}

// Runs build/bench/PROGRAM ARGS --csv out.csv: stdout is the file's text.
void expect_stdout_is_the_csv(const std::string& program, const std::string& args, const std::string& first_column) {
  igac_test::TempDir tmp("bench");
  const fs::path exe = fs::path(IGAC_BINARY).parent_path() / "bench" / program;
  ASSERT_TRUE(fs::exists(exe)) << exe;
  const std::string cmd = "cd " + igac_test::quote(tmp.path().string()) + " && " + igac_test::quote(exe.string()) + " " +
                          args + " --csv out.csv 2>/dev/null";
  int status = 0;
  const std::string out = command_output(cmd, &status);
  ASSERT_EQ(status, 0) << program << ": " << out;
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

// build/bench/inf_sup's beta_h column for ARGS (one row per mesh), found by
// its header's name.
std::vector<double> inf_sup_betas(const std::string& args) {
  const fs::path exe = fs::path(IGAC_BINARY).parent_path() / "bench" / "inf_sup";
  int status = 0;
  const std::string out = command_output(igac_test::quote(exe.string()) + " " + args + " 2>/dev/null", &status);
  EXPECT_EQ(status, 0) << args;
  std::vector<double> betas;
  std::istringstream in(out);
  std::string line, cell;
  std::getline(in, line);  // the header
  int column = 0;
  for (std::istringstream header(line); std::getline(header, cell, ',') && cell != "beta";) ++column;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    for (int k = 0; k <= column; ++k) std::getline(row, cell, ',');
    betas.push_back(std::stod(cell));
  }
  return betas;
}

// The pairs of engine/pressure_space.hpp on C^1 quadratics, every side
// clamped (docs/benchmarks.md, "Inf-sup"): the sub-grid continuous pressure
// of `formulation = "mixed"` (degree 1 on breakpoints twice coarser) is
// stable, beta_h 0.652, 0.623, 0.607 at n = 4, 8, 16 with the consistent
// pressure mass, 0.258, 0.288, 0.301 with the lumped one the formulation
// uses; the same space on the displacement's own breakpoints is not (0.449,
// 0.311, 0.193), nor are constants per element (0.513, 0.313, 0.165).
TEST(BenchPrograms, InfSupStaysBoundedForTheSubGridPressureAndFallsOnTheSameGrid) {
  const std::vector<double> mixed = inf_sup_betas("4 8 16"), lumped = inf_sup_betas("--lumped 4 8 16"),
                            same = inf_sup_betas("--same-grid 4 8 16"),
                            element = inf_sup_betas("--formulation mixed_element 4 8 16");
  ASSERT_EQ(mixed.size(), 3u);
  ASSERT_EQ(lumped.size(), 3u);
  ASSERT_EQ(same.size(), 3u);
  ASSERT_EQ(element.size(), 3u);
  const double expected[3] = {0.652, 0.623, 0.607}, expected_lumped[3] = {0.258, 0.288, 0.301};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(mixed[size_t(k)], expected[k], 1e-3) << "n = " << (4 << k);
    EXPECT_NEAR(lumped[size_t(k)], expected_lumped[k], 1e-3) << "n = " << (4 << k);
  }
  EXPECT_LT(same[2], 0.5 * same[0]);        // 0.193 against 0.449
  EXPECT_LT(element[2], 0.5 * element[0]);  // 0.165 against 0.513
}

// A bad option is one line on stderr naming it, exit 2, nothing on stdout.
TEST(BenchPrograms, InfSupRefusesBadOptionsInOneLine) {
  const fs::path exe = fs::path(IGAC_BINARY).parent_path() / "bench" / "inf_sup";
  for (const std::string args : {"--clamp x 4", "--formulation nope 4", "--same-grid --macro 2 4", "--macro 3 4", "4x"}) {
    int status = 0;
    const std::string out = command_output(igac_test::quote(exe.string()) + " " + args + " 2>&1", &status);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << args << ": " << out;
    EXPECT_EQ(out.rfind("inf_sup: ", 0), 0u) << args << ": " << out;
    EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << args << ": " << out;
  }
}

}  // namespace
