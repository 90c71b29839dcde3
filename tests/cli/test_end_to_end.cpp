// SPDX-License-Identifier: BSD-3-Clause
// End to end through the igac executable: a coarse 3D Hertz run, a 3D
// Neo-Hookean contact smoke test, and the contents of study.json, study.csv,
// pressure.csv and load_curve.csv (what a user's scripts read), with the
// SVG plots beside them.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;
using igac_test::quote;
using igac_test::run_igac;
using igac_test::TempDir;
const std::string kCases = std::string(IGAC_SOURCE_DIR) + "/cases/";

nlohmann::json json_of(const fs::path& p) { return nlohmann::json::parse(igac_test::read_file(p)); }


// A plot igac wrote (io/plots.hpp): an SVG document with one frame per
// panel and something drawn in it.
void expect_svg(const fs::path& p) {
  ASSERT_TRUE(fs::exists(p)) << p;
  pugi::xml_document doc;
  const std::string text = igac_test::read_file(p);
  ASSERT_TRUE(doc.load_string(text.c_str())) << p;
  EXPECT_STREQ(doc.document_element().name(), "svg") << p;
  EXPECT_FALSE(doc.select_nodes("//rect[@class='frame']").empty()) << p;
  EXPECT_FALSE(doc.select_nodes("//g[@class='series']/path").empty()) << p;
}

// cases/NAME.toml with edits, written to dir/NAME.toml.
fs::path edited(const std::string& name, const std::vector<std::pair<std::string, std::string>>& edits, const fs::path& dir) {
  std::string s = igac_test::read_file(kCases + name + ".toml");
  for (const auto& [from, to] : edits) {
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) s.replace(at, from.size(), to);
  }
  const fs::path p = dir / (name + ".toml");
  std::ofstream(p) << s;
  return p;
}

TEST(EndToEnd, Hertz3DCoarse) {
  TempDir tmp("h3");
  const fs::path c = edited("hertz3d", {{"elements = [", "elements = [8, 4, 8] # was ["}}, tmp.path());
  const auto o = run_igac("run " + quote(c.string()) + " --quiet --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto j = json_of(tmp.path() / "out" / "summary.json");
  EXPECT_EQ(j["dim"], 3);
  EXPECT_EQ(j["status"], "converged");
  const double applied = j["contact"]["applied_force"], total = j["contact"]["total_force"];
  EXPECT_NEAR(total / applied, 1.0, 1e-10) << "the contact carries the load";
  const double p0 = j["analytic"]["max_pressure"], a = j["analytic"]["half_width"];
  std::printf("8 x 4 x 8: peak / p0 %.6f, half width / a %.6f\n", double(j["contact"]["max_pressure"]) / p0,
              double(j["contact"]["half_width"]) / a);
  // Measured at a01e0b0 on this 8 x 4 x 8 mesh (1/4 of hertz3d's spans per
  // direction): peak -1.62 %, half width -0.38 %.  3 % on both (was 35 %):
  // a margin of 1.9 on the peak, more on the half width, whose contact edge
  // is read inside a coarse span.
  constexpr double kCoarseBand = 0.03;
  EXPECT_NEAR(double(j["contact"]["max_pressure"]) / p0, 1.0, kCoarseBand) << "coarse, but the Hertz peak";
  EXPECT_NEAR(double(j["contact"]["half_width"]) / a, 1.0, kCoarseBand);
}

TEST(EndToEnd, NeoHookean3DContactSmoke) {
  TempDir tmp("nh3");
  const fs::path c = edited("hertz3d_neohookean",
                            {{"elements = [12, 3, 12]", "elements = [6, 2, 6]"}}, tmp.path());
  const auto o = run_igac("run " + quote(c.string()) + " --quiet --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto j = json_of(tmp.path() / "out" / "summary.json");
  EXPECT_EQ(j["status"], "converged");
  EXPECT_GT(j["contact"]["active"].get<int>(), 0);
  EXPECT_NEAR(double(j["contact"]["total_force"]) / double(j["contact"]["applied_force"]), 1.0, 1e-6);
  const auto rows = igac_test::csv_rows(tmp.path() / "out" / "load_curve.csv");
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"load_factor", "contact_force", "face_displacement", "obstacle_displacement",
                                               "reaction_left_x", "reaction_left_y", "reaction_left_z",
                                               "reaction_back_x", "reaction_back_y", "reaction_back_z"}));
  EXPECT_DOUBLE_EQ(std::stod(rows.back()[0]), 1.0);
  for (size_t i = 2; i < rows.size(); ++i) EXPECT_GT(std::stod(rows[i][1]), std::stod(rows[i - 1][1])) << "force grows";
  expect_svg(tmp.path() / "out" / "load_curve.svg");
  expect_svg(tmp.path() / "out" / "pressure.svg");
}

TEST(EndToEnd, StudyJsonAndCsvAgree) {
  TempDir tmp("study");
  const auto o = run_igac("study " + quote(kCases + "lame_cylinder.toml") + " --levels 3 --quiet --out st", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto j = json_of(tmp.path() / "st" / "study.json");
  const auto rows = igac_test::csv_rows(tmp.path() / "st" / "study.csv");
  ASSERT_TRUE(j.contains("levels"));
  ASSERT_EQ(j["levels"].size(), 3u);
  ASSERT_EQ(rows.size(), 4u) << "header and one row per level";
  EXPECT_EQ(rows[0][0], "level");
  // The L2 rate of the Lame cylinder at p = 2 is 3 (the closed form is the
  // reference); measured 3.084 between levels 1 and 2 (pre-asymptotic, 3.035
  // a level further): within 0.3 of 3.
  const auto& rates = j["rates"]["displacement_l2"];
  ASSERT_EQ(rates.size(), 2u);
  EXPECT_NEAR(rates.back().get<double>(), 3.0, 0.3);
  // The CSV carries the same errors as the JSON.
  const auto header = rows[0];
  const auto col = std::find(header.begin(), header.end(), "displacement_l2") - header.begin();
  ASSERT_LT(size_t(col), header.size());
  for (int l = 0; l < 3; ++l)
    EXPECT_NEAR(std::stod(rows[l + 1][col]) / j["levels"][l]["errors"]["displacement_l2"].get<double>(), 1.0, 1e-7);
  expect_svg(tmp.path() / "st" / "study.svg");
}

TEST(EndToEnd, PressureCsvMatchesTheSummary) {
  TempDir tmp("pcsv");
  const auto o = run_igac("run " + quote(kCases + "hertz2d.toml") + " --quiet --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto j = json_of(tmp.path() / "out" / "summary.json");
  const auto rows = igac_test::csv_rows(tmp.path() / "out" / "pressure.csv");
  ASSERT_EQ(rows[0], (std::vector<std::string>{"kind", "r", "pressure", "r_over_a", "p_over_p0", "hertz_p_over_p0"}));
  int multipliers = 0;
  double max_p = 0;
  for (size_t i = 1; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), 6u) << i;
    if (rows[i][0] != "multiplier") continue;
    ++multipliers;
    const double p = std::stod(rows[i][2]);
    EXPECT_GE(p, 0.0) << "a rigid obstacle only pushes";
    max_p = std::max(max_p, p);
  }
  EXPECT_EQ(multipliers, j["multipliers"].get<int>());
  EXPECT_NEAR(max_p, j["contact"]["max_pressure"].get<double>(), 1e-9);
  expect_svg(tmp.path() / "out" / "pressure.svg");
  EXPECT_FALSE(fs::exists(tmp.path() / "out" / "load_curve.svg")) << "small deformation: no load curve";
  for (const auto& e : fs::directory_iterator(tmp.path() / "out"))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << "a temporary file was left: " << e.path();
}

}  // namespace
