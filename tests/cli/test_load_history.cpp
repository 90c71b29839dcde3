// SPDX-License-Identifier: BSD-3-Clause
// A case with load curves through the igac executable (docs/case_file.md,
// "Load curves"): the .pvd plays the steps at the curves' time, one frame
// per step with the undeformed frame at 0; load_curve.csv starts with the
// time and ends with the reactions of every [[dirichlet]] face set, which
// balance the pressure at each step; summary.json gives each step its time.
#include <gtest/gtest.h>

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

}  // namespace
