// SPDX-License-Identifier: BSD-3-Clause
// A case with load curves through the igac executable (docs/case_file.md,
// "Load curves"): the .pvd plays the steps at the curves' time, one frame
// per step with the undeformed frame at 0; load_curve.csv starts with the
// time and ends with the reactions of every [[dirichlet]] face set, which
// balance the pressure at each step; summary.json gives each step its time.
// With friction: load_curve.csv's tangential_force column and the loop's
// panel in load_curve.svg, the console's status line (its restart:
// tests/cli/test_restart.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;


TEST(LoadHistory, PvdTimesCsvColumnsAndReactionsPerStep) {
  igac_test::TempDir tmp("curves");
  const std::string path = std::string(IGAC_SOURCE_DIR) + "/tests/data/curve_block.toml";
  const auto o = igac_test::run_igac("run " + igac_test::quote(path) + " --quiet --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const fs::path out = tmp.path() / "out";
  // Steps: [0, 1] in 2, [1, 1.5] in 1, [1.5, 2.5] in 2.
  const std::vector<double> times{0.5, 1, 1.5, 2, 2.5};
  const std::string pvd = igac_test::read_file(out / "solution.pvd");
  std::vector<double> frames;
  const std::regex timestep("timestep=\"([^\"]+)\" part=\"0\"");
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), timestep); it != std::sregex_iterator(); ++it)
    frames.push_back(std::stod((*it)[1]));
  std::vector<double> expected{0};
  expected.insert(expected.end(), times.begin(), times.end());
  EXPECT_EQ(frames, expected);
  const auto rows = igac_test::csv_rows(out / "load_curve.csv");
  ASSERT_EQ(rows.size(), times.size() + 1);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"time", "contact_force", "face_displacement", "obstacle_displacement",
                                               "reaction_left_x", "reaction_left_y", "reaction_bottom_x",
                                               "reaction_bottom_y"}));
  const double factor[] = {0.5, 1, 0.5, 0.5, 0.5};
  for (size_t i = 0; i < times.size(); ++i) {
    EXPECT_EQ(std::stod(rows[i + 1][0]), times[i]);
    // the left face holds P times its length (1) at the step's factor (10 printed digits)
    EXPECT_NEAR(std::stod(rows[i + 1][4]), -0.05 * factor[i], 1e-10) << "t = " << times[i];
  }
  const auto summary = igac_test::read_summary(out);
  ASSERT_EQ(summary["load_steps"].size(), times.size());
  for (size_t i = 0; i < times.size(); ++i) EXPECT_EQ(summary["load_steps"][i]["time"].get<double>(), times[i]);
  EXPECT_EQ(summary["status"], "converged");
}

// The sliding block of tests/data/curve_friction_block.toml, with `model`.
std::string dragged_block(const std::string& model) {
  const std::string text = igac_test::read_file(std::string(IGAC_SOURCE_DIR) + "/tests/data/curve_friction_block.toml");
  return std::regex_replace(text, std::regex(R"(model = "linear_elastic")"), "model = \"" + model + "\"");
}

TEST(LoadHistory, FrictionTangentialForceColumnAndLoopPanel) {
  igac_test::TempDir tmp("friction_curves");
  std::ofstream(tmp.path() / "block.toml") << dragged_block("linear_elastic");
  const auto o = igac_test::run_igac("run block.toml --quiet --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto rows = igac_test::csv_rows(tmp.path() / "out" / "load_curve.csv");
  ASSERT_EQ(rows.size(), 7u);  // the header and 6 steps
  const size_t tc = igac_test::csv_column(rows, "tangential_force"), oc = 3;
  ASSERT_GT(tc, 0u);  // (found)
  EXPECT_EQ(rows[0][oc], "obstacle_displacement");
  // t = 2: dragged to +0.01, sliding: f N = 0.003; t = 3: back at 0, -f N.
  EXPECT_EQ(std::stod(rows[4][oc]), 0.01);
  EXPECT_NEAR(std::stod(rows[4][tc]), 0.003, 1e-12);
  EXPECT_EQ(std::stod(rows[6][oc]), 0.0);
  EXPECT_NEAR(std::stod(rows[6][tc]), -0.003, 1e-12);
  const std::string svg = igac_test::read_file(tmp.path() / "out" / "load_curve.svg");
  EXPECT_NE(svg.find("tangential force (first tangent)"), std::string::npos);
  // The console of a small-deformation run in steps: active-set iterations,
  // the small-deformation contact lines (no Newton, no Cauchy pressure).
  const auto loud = igac_test::run_igac("run block.toml --out loud", tmp.path());
  ASSERT_EQ(loud.exit_code, 0) << loud.output;
  EXPECT_TRUE(std::regex_search(loud.output, std::regex("converged \\(6 load steps, [0-9]+ active-set iterations\\)")))
      << loud.output;
  EXPECT_EQ(loud.output.find("Newton"), std::string::npos) << loud.output;
  EXPECT_EQ(loud.output.find("Cauchy"), std::string::npos) << loud.output;
}

// Large deformation: the same block, Neo-Hookean,
// through the executable: load_curve.csv's tangential_force is +f N at the
// turn and -f N back at 0 (to its 10 printed digits and the Newton
// tolerance).
TEST(LoadHistory, LargeDeformationFrictionColumn) {
  igac_test::TempDir tmp("friction_curves_large");
  std::ofstream(tmp.path() / "block.toml") << dragged_block("neo_hookean");
  const auto o = igac_test::run_igac("run block.toml --quiet --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto rows = igac_test::csv_rows(tmp.path() / "out" / "load_curve.csv");
  const size_t tc = igac_test::csv_column(rows, "tangential_force"), oc = 3;
  ASSERT_GT(tc, 0u);  // (found)
  bool turn = false, back = false;
  for (size_t i = 1; i < rows.size(); ++i) {
    const double t = std::stod(rows[i][0]);
    if (t == 2.0) {
      turn = true;
      EXPECT_EQ(std::stod(rows[i][oc]), 0.01);
      EXPECT_NEAR(std::stod(rows[i][tc]), 0.003, 1e-11);
    }
    if (t == 3.0) {
      back = true;
      EXPECT_NEAR(std::stod(rows[i][tc]), -0.003, 1e-11);
    }
  }
  EXPECT_TRUE(turn && back);
}

}  // namespace
