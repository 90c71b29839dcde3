// SPDX-License-Identifier: BSD-3-Clause
// What the console and the summary tell a user while and after a run
// (issue 25): the header before the progress lines, a line per active-set
// iteration, --quiet quiet; the [units] labels.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;

// cases/hertz2d.toml with `extra` appended, written to dir/hertz2d.toml.
fs::path hertz_with(const std::string& extra, const fs::path& dir) {
  const fs::path p = dir / "hertz2d.toml";
  std::ofstream(p) << igac_test::read_file(std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml") << "\n" << extra;
  return p;
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(Console, HeaderFirstThenALinePerActiveSetIteration) {
  igac_test::TempDir tmp("progress");
  const fs::path c = hertz_with("", tmp.path());
  const auto o = igac_test::run_igac("run " + igac_test::quote(c.string()) + " --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto j = igac_test::read_summary(tmp.path() / "out");
  EXPECT_EQ(o.output.rfind("igac: hertz2d — 2D", 0), 0u) << o.output;  // the very first line
  const size_t first = o.output.find("active set   1: ");
  ASSERT_NE(first, std::string::npos) << o.output;
  EXPECT_LT(first, o.output.find("  status        converged")) << o.output;
  EXPECT_EQ(count_of(o.output, "\nactive set "), j["contact"]["active_set_iterations"].get<size_t>()) << o.output;
  EXPECT_NE(o.output.find(" active, 0 changing ("), std::string::npos) << o.output;  // the last one settles

  const auto q = igac_test::run_igac("run " + igac_test::quote(c.string()) + " --out out2 --quiet", tmp.path());
  ASSERT_EQ(q.exit_code, 0) << q.output;
  EXPECT_EQ(q.output, "");
}

TEST(Console, UnitsAreLabelsEchoedInTheSummaryConsoleAndPlots) {
  igac_test::TempDir tmp("units");
  const fs::path c = hertz_with("[units]\nsystem = \"mm-N-MPa\"\n", tmp.path());
  const auto o = igac_test::run_igac("run " + igac_test::quote(c.string()) + " --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto j = igac_test::read_summary(tmp.path() / "out");
  EXPECT_EQ(j["units"], nlohmann::json::parse(R"({"system": "mm-N-MPa", "length": "mm", "force": "N", "stress": "MPa"})"));
  EXPECT_NE(o.output.find("  units         length mm, force N, stress MPa (labels only"), std::string::npos) << o.output;

  // Without the table: "consistent units"; the plots' axes name no unit.
  const fs::path plain = hertz_with("", tmp.path());
  const auto p = igac_test::run_igac("run " + igac_test::quote(plain.string()) + " --out plain --quiet", tmp.path());
  ASSERT_EQ(p.exit_code, 0) << p.output;
  EXPECT_EQ(igac_test::read_summary(tmp.path() / "plain")["units"]["system"], "consistent units");

  // One key overrides the system's name; an unknown system, or key, is refused.
  const fs::path own = hertz_with("[units]\nsystem = \"SI\"\nstress = \"GPa\"\n", tmp.path());
  ASSERT_EQ(igac_test::run_igac("run " + igac_test::quote(own.string()) + " --out own --quiet", tmp.path()).exit_code, 0);
  const auto u = igac_test::read_summary(tmp.path() / "own")["units"];
  EXPECT_EQ(u["length"], "m");
  EXPECT_EQ(u["stress"], "GPa");
  const fs::path bad = hertz_with("[units]\nsystem = \"imperial\"\n", tmp.path());
  const auto b = igac_test::run_igac("run " + igac_test::quote(bad.string()) + " --no-output", tmp.path());
  EXPECT_EQ(b.exit_code, 2);
  EXPECT_NE(b.output.find("unknown system 'imperial'"), std::string::npos) << b.output;
  const fs::path typo = hertz_with("[units]\nlenght = \"mm\"\n", tmp.path());
  const auto t = igac_test::run_igac("run " + igac_test::quote(typo.string()) + " --no-output", tmp.path());
  EXPECT_EQ(t.exit_code, 2);
  EXPECT_NE(t.output.find("length"), std::string::npos) << t.output;  // did you mean
}

// The pressure plot of a case against a plane (no Hertz scale) names its
// axes' units.
TEST(Console, PlotAxesCarryTheUnits) {
  igac_test::TempDir tmp("axes");
  std::string s = igac_test::read_file(std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml");
  s.replace(s.find("solution = \"hertz\""), 18, "solution = \"none\"");
  std::ofstream(tmp.path() / "plain.toml") << s << "\n[units]\nsystem = \"mm-N-MPa\"\n";
  const auto o = igac_test::run_igac("run plain.toml --out out --quiet", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::string svg = igac_test::read_file(tmp.path() / "out" / "pressure.svg");
  EXPECT_NE(svg.find("[MPa]"), std::string::npos);
  EXPECT_NE(svg.find("[mm]"), std::string::npos);
}

}  // namespace
