// SPDX-License-Identifier: BSD-3-Clause
// igac run --restart (app/restart.hpp, io/state_file.hpp): a run stopped
// after step k (--stop-after-step) and continued from its output ends where
// an uninterrupted run ends: every number of the final summary.json equal
// to 1e-12 relative (the bar; the steps are the same, bit for bit),
// in small deformation (load curves, contact) and in large deformation
// (the Newton driver, its increments and predictor state carried over);
// --from-step continues from an earlier step of a finished run; a restart
// against another case file is refused in one line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string data(const std::string& name) { return igac_test::quote(std::string(IGAC_SOURCE_DIR) + "/tests/data/" + name); }

// What measures the machine or names the folder, not the result.
const std::regex kNotResults("time|timing|seconds|_s$|memory|resident|path|folder");

// Every number of `a` equals `b`'s to 1e-12 relative, every other value exactly.
void expect_same(const json& a, const json& b, const std::string& where, int& numbers) {
  ASSERT_EQ(a.type() == json::value_t::number_unsigned ? json::value_t::number_integer : a.type(),
            b.type() == json::value_t::number_unsigned ? json::value_t::number_integer : b.type())
      << where;
  if (a.is_object()) {
    ASSERT_EQ(a.size(), b.size()) << where;
    for (const auto& [k, v] : a.items()) {
      if (std::regex_search(k, kNotResults)) continue;
      ASSERT_TRUE(b.contains(k)) << where << "." << k;
      expect_same(v, b[k], where + "." + k, numbers);
    }
  } else if (a.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << where;
    for (size_t i = 0; i < a.size(); ++i) expect_same(a[i], b[i], where + "[" + std::to_string(i) + "]", numbers);
  } else if (a.is_number_float()) {
    constexpr double kRelative = 1e-12;  // issue 25's bar
    const double x = a.get<double>(), y = b.get<double>();
    EXPECT_LE(std::abs(x - y), kRelative * std::max(std::abs(x), std::abs(y))) << where;
    ++numbers;
  } else {
    EXPECT_EQ(a, b) << where;
  }
}

// Runs `case_file` whole, then to step k and on from there; the two final
// summaries agree (and with `vtk`, the .pvd).
void expect_restart_matches(const std::string& case_file, int k, bool vtk) {
  igac_test::TempDir tmp("restart");
  const auto whole = igac_test::run_igac("run " + data(case_file) + " --quiet --out whole", tmp.path());
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  const auto part = igac_test::run_igac(
      "run " + data(case_file) + " --quiet --out part --stop-after-step " + std::to_string(k), tmp.path());
  ASSERT_EQ(part.exit_code, 0) << part.output;
  const json stopped = igac_test::read_summary(tmp.path() / "part");
  EXPECT_EQ(stopped["load_steps"].size(), size_t(k));
  EXPECT_EQ(stopped["status"], "stopped after step " + std::to_string(k) + " (as asked)");
  const auto resumed = igac_test::run_igac("run " + data(case_file) + " --quiet --out part --restart part", tmp.path());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const json a = igac_test::read_summary(tmp.path() / "whole"), b = igac_test::read_summary(tmp.path() / "part");
  int numbers = 0;
  expect_same(a, b, "summary.json", numbers);
  EXPECT_GT(numbers, 20);
  EXPECT_EQ(igac_test::read_file(tmp.path() / "whole" / "load_curve.csv"),
            igac_test::read_file(tmp.path() / "part" / "load_curve.csv"));
  // The .pvd plays every step, the earlier ones copied.
  const std::string pvd_a = igac_test::read_file(tmp.path() / "whole" / "solution.pvd");
  EXPECT_EQ(pvd_a.empty(), !vtk);
  EXPECT_EQ(pvd_a, igac_test::read_file(tmp.path() / "part" / "solution.pvd"));
  for (int step = 0; vtk && step <= k + 1; ++step)
    EXPECT_TRUE(fs::exists(tmp.path() / "part" / ("solution_000" + std::to_string(step) + ".vtu"))) << step;
  // And from an earlier step of the finished run.
  const auto from = igac_test::run_igac(
      "run " + data(case_file) + " --quiet --out from --restart whole --from-step " + std::to_string(k - 1), tmp.path());
  ASSERT_EQ(from.exit_code, 0) << from.output;
  numbers = 0;
  expect_same(a, igac_test::read_summary(tmp.path() / "from"), "summary.json (--from-step)", numbers);
}

TEST(Restart, LargeDeformationContinuesAsIfUninterrupted) { expect_restart_matches("curve_block_neohookean.toml", 3, true); }

TEST(Restart, SmallDeformationContinuesAsIfUninterrupted) { expect_restart_matches("curve_contact.toml", 2, false); }

TEST(Restart, AnotherCaseFileIsRefusedInOneLine) {
  igac_test::TempDir tmp("restart");
  ASSERT_EQ(igac_test::run_igac("run " + data("curve_block.toml") + " --quiet --out a", tmp.path()).exit_code, 0);
  const auto o = igac_test::run_igac("run " + data("curve_contact.toml") + " --quiet --out b --restart a", tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  EXPECT_NE(o.output.find("--restart a: that run was of another case file"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(tmp.path() / "b"));
  // A step the run did not write, and a case solved in one step: one line each.
  const auto beyond = igac_test::run_igac("run " + data("curve_block.toml") + " --quiet --out c --restart a --from-step 99",
                                          tmp.path());
  EXPECT_EQ(beyond.exit_code, 2) << beyond.output;
  EXPECT_NE(beyond.output.find("--from-step 99: the run in a wrote the states of steps 1 to 5"), std::string::npos)
      << beyond.output;
  const auto one_step = igac_test::run_igac(
      "run " + igac_test::quote(std::string(IGAC_SOURCE_DIR) + "/cases/lame_cylinder.toml") + " --quiet --restart a",
      tmp.path());
  EXPECT_EQ(one_step.exit_code, 2) << one_step.output;
  EXPECT_NE(one_step.output.find("need a run in steps"), std::string::npos) << one_step.output;
}

}  // namespace
