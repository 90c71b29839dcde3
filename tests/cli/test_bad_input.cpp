// SPDX-License-Identifier: BSD-3-Clause
// Bad input never crashes and never writes a half result (docs/design.md,
// "Errors and exit codes"): each bad case in tests/data/bad_*.toml (cases/lame_cylinder.toml with one
// defect) is run through the igac executable, which must exit with code 2
// and print exactly one line "igac: error: FILE[:LINE]: [section] key: reason"
// and create no output folder.  Defects that a case file cannot express
// (knot vectors, weights) are checked through the library.  A good run, for
// contrast, writes summary.json with the keys docs/design.md ("Outputs") promises.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/spline/knot_vector.hpp"
#include "engine/spline/nurbs_patch.hpp"
#include "engine/geometry/shapes.hpp"
#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;
using igac_test::Outcome;
using igac_test::quote;
using igac_test::run_igac;
using igac_test::TempDir;

// Exit code of igac for bad input (app/main.cpp; docs/design.md, "Errors and exit codes").
constexpr int kBadInputExit = 2;

std::string data_file(const std::string& name) { return std::string(IGAC_SOURCE_DIR) + "/tests/data/" + name; }

// The 1-based line of the first line of `file` containing `text` (comment
// lines, which may quote a key, left out).
int line_of(const std::string& file, const std::string& text) {
  std::ifstream in(file);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n)
    if (line.rfind("#", 0) != 0 && line.find(text) != std::string::npos) return n;
  ADD_FAILURE() << "'" << text << "' not in " << file;
  return 0;
}

// Checks the one-line error message of a rejected run.
void expect_rejected(const Outcome& o, const std::vector<std::string>& fragments) {
  EXPECT_EQ(o.exit_code, kBadInputExit) << o.output;
  ASSERT_FALSE(o.output.empty()) << "no message at all";
  EXPECT_EQ(o.output.rfind("igac: error: ", 0), 0u) << "message must start with 'igac: error: ': " << o.output;
  EXPECT_EQ(o.output.back(), '\n');
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << "exactly one line: " << o.output;
  for (const auto& f : fragments) EXPECT_NE(o.output.find(f), std::string::npos) << "'" << f << "' in: " << o.output;
}

struct BadCase {
  std::string name;                    // test name
  std::string file;                    // in tests/data
  std::string line_marker;             // text on the offending line ("" = no line number expected)
  std::vector<std::string> fragments;  // section and key, and the reason
};

// gtest (and CTest's test names) print the case by its name.
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class BadInputFile : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInputFile, ExitsTwoWithOneLineAndWritesNothing) {
  const BadCase& c = GetParam();
  const std::string path = data_file(c.file);
  ASSERT_TRUE(fs::is_regular_file(path)) << path;
  TempDir tmp("bad");
  const fs::path out = tmp.path() / "out";
  const Outcome o = run_igac("run " + quote(path) + " --out " + quote(out.string()), tmp.path());
  std::vector<std::string> expect = c.fragments;
  // The file, with the line of the offending key when the key is in the file.
  expect.push_back(c.line_marker.empty() ? path + ": " : path + ":" + std::to_string(line_of(path, c.line_marker)) + ": ");
  expect_rejected(o, expect);
  EXPECT_FALSE(fs::exists(out)) << "an output folder was created";
  EXPECT_TRUE(tmp.empty()) << "something was written in the working directory";
  // The same without --out: nothing appears under the default out/<name>.
  const Outcome o2 = run_igac("run " + quote(path), tmp.path());
  EXPECT_EQ(o2.exit_code, kBadInputExit);
  EXPECT_EQ(o2.output, o.output) << "the message does not depend on --out";
  EXPECT_TRUE(tmp.empty()) << "a default output folder was created";
}

INSTANTIATE_TEST_SUITE_P(
    BadInput, BadInputFile,
    ::testing::Values(
        BadCase{"malformed_toml", "bad_malformed.toml", "[material", {"malformed TOML", "expected ']'"}},
        BadCase{"unknown_top_level_key", "bad_unknown_top_key.toml", "solvers =", {"[top level] solvers: unknown key"}},
        BadCase{"unknown_material_key", "bad_unknown_material_key.toml", "poisson =", {"[material] poisson: unknown key", "nu"}},
        BadCase{"missing_E", "bad_missing_E.toml", "[material]", {"[material] E: missing"}},  // (its table's line)
        BadCase{"degree_0", "bad_degree_0.toml", "degree = 0", {"[mesh] degree:", "at least 1"}},
        BadCase{"E_not_a_number", "bad_E_not_a_number.toml", "E = \"1000\"", {"[material] E: must be a number"}},
        BadCase{"E_negative", "bad_E_negative.toml", "E = -1000", {"[material] E:", "must be positive"}},
        BadCase{"nu_one_half", "bad_nu_half.toml", "nu = 0.5", {"[material] nu:", "0.5", "(-1, 0.5)"}},
        BadCase{"nu_below_minus_one", "bad_nu_below_minus_one.toml", "nu = -1.2", {"[material] nu:", "-1.2", "(-1, 0.5)"}},
        BadCase{"unknown_pressure_face", "bad_unknown_face.toml", "faces = [\"innner\"]",
                {"[pressure] faces:", "unknown face 'innner'", "inner"}},
        BadCase{"unknown_shape", "bad_unknown_shape.toml", "shape =", {"[geometry] shape:", "unknown shape 'hexagon'"}},
        BadCase{"refine_30", "bad_refine_30.toml", "refine = 30", {"[mesh] refine = 30", "GiB", "more than this machine"}},
        BadCase{"unknown_formulation", "bad_unknown_formulation.toml", "formulation =",
                {"[material] formulation:", "unknown formulation 'fbar'", "mixed"}},
        BadCase{"bulk_modulus_negative", "bad_bulk_negative.toml", "bulk_modulus =", {"[material] bulk_modulus:", "positive"}},
        BadCase{"bulk_modulus_nan", "bad_bulk_nan.toml", "bulk_modulus =", {"[material] bulk_modulus:"}},
        BadCase{"mixed_without_split", "bad_mixed_without_split.toml", "formulation =",
                {"[material] formulation:", "'saint_venant_kirchhoff' declares none"}},
        BadCase{"incompressible_not_mixed", "bad_incompressible_not_mixed.toml", "incompressible =",
                {"[material] incompressible:", "formulation = \"mixed\""}},
        BadCase{"incompressible_linear_elastic", "bad_incompressible_linear.toml", "incompressible =",
                {"[material] incompressible:", "large-deformation"}},
        BadCase{"traction_components", "bad_traction_components.toml", "value = [0.0, 1.0, 0.0]",
                {"[traction] value:", "must have 2 entries, has 3"}},
        BadCase{"curve_times_not_increasing", "bad_curve_times_not_increasing.toml", "curve =",
                {"[pressure] curve:", "the times must increase: 0.5 follows 1"}},
        BadCase{"curve_not_finite", "bad_curve_nan.toml", "curve =", {"[pressure] curve:", "non-finite"}},
        BadCase{"curve_not_pairs", "bad_curve_not_pairs.toml", "curve =",
                {"[pressure] curve:", "must be a list of [time, factor] pairs"}},
        BadCase{"curve_without_load", "bad_curve_no_load.toml", "curve =",
                {"[dirichlet] curve:", "no prescribed value for the curve to scale"}},
        BadCase{"line_search_unknown", "bad_line_search_unknown.toml", "line_search =",
                {"[loading] line_search:", "\"halving\""}},
        BadCase{"active_set_unknown", "bad_active_set_unknown.toml", "active_set =",
                {"[loading] active_set:", "\"linearised\"", "\"semismooth\""}}),
    [](const ::testing::TestParamInfo<BadCase>& info) { return info.param.name; });

TEST(BadInput, RefineOptionBeyondMemory) {
  TempDir tmp("bad");
  const std::string c = std::string(IGAC_SOURCE_DIR) + "/cases/lame_cylinder.toml";
  const Outcome o = run_igac("run " + quote(c) + " --refine 30 --out " + quote((tmp.path() / "out").string()), tmp.path());
  expect_rejected(o, {c, "refine", "30", "GiB"});
  EXPECT_TRUE(tmp.empty());
}

TEST(BadInput, DegreeOptionBelowOne) {
  TempDir tmp("bad");
  const std::string c = std::string(IGAC_SOURCE_DIR) + "/cases/lame_cylinder.toml";
  const Outcome o = run_igac("run " + quote(c) + " --degree 0 --out " + quote((tmp.path() / "out").string()), tmp.path());
  expect_rejected(o, {"--degree 0", "1..10"});
  EXPECT_TRUE(tmp.empty());
}

TEST(BadInput, StudyWithOneLevel) {
  TempDir tmp("bad");
  const std::string c = std::string(IGAC_SOURCE_DIR) + "/cases/lame_cylinder.toml";
  const Outcome o = run_igac("study " + quote(c) + " --levels 1 --out " + quote((tmp.path() / "out").string()), tmp.path());
  expect_rejected(o, {"--levels 1", "at least 2 levels"});
  EXPECT_TRUE(tmp.empty());
}

// docs/design.md, "Errors and exit codes": bad input gives one line naming
// the problem and exit code 2; a command-line typo is bad input like any other.
TEST(BadInput, UnknownCommandLineOption) {
  TempDir tmp("bad");
  const std::string c = std::string(IGAC_SOURCE_DIR) + "/cases/lame_cylinder.toml";
  const Outcome o = run_igac("run " + quote(c) + " --bogus-option --out " + quote((tmp.path() / "out").string()), tmp.path());
  expect_rejected(o, {"--bogus-option"});
  EXPECT_TRUE(tmp.empty());
}

// bench/hostile_inputs.py: `igac solve case.toml` said "A subcommand is
// required", not which word it did not know.
TEST(BadInput, UnknownCommandIsNamed) {
  TempDir tmp("bad");
  const Outcome o = run_igac("solve case.toml", tmp.path());
  expect_rejected(o, {"unknown command 'solve'", "run, study or geometry"});
  EXPECT_TRUE(tmp.empty());
}

TEST(BadInput, MissingCaseFile) {
  TempDir tmp("bad");
  const Outcome o = run_igac("run no_such_case.toml --out " + quote((tmp.path() / "out").string()), tmp.path());
  expect_rejected(o, {"no_such_case.toml", "no such case file"});
  EXPECT_TRUE(tmp.empty());
}

// Not expressible in a case file: the library must refuse them with a
// message naming the problem.
TEST(BadInput, InvalidKnotVectorThrowsSplineError) {
  try {
    igac::KnotVector(2, {0, 0, 0, 0.7, 0.3, 1, 1, 1});
    ADD_FAILURE() << "decreasing knots accepted";
  } catch (const igac::SplineError& e) {
    EXPECT_NE(std::string(e.what()).find("knots decrease"), std::string::npos) << e.what();
  }
  try {
    igac::KnotVector(2, {0, 0, 0.5, 1, 1, 1});
    ADD_FAILURE() << "a knot vector that is not open accepted";
  } catch (const igac::SplineError& e) {
    EXPECT_NE(std::string(e.what()).find("not open"), std::string::npos) << e.what();
  }
}

TEST(BadInput, NegativeWeightThrowsSplineError) {
  const igac::NurbsPatch p = igac::quarter_disc(1.0).patch;
  Eigen::VectorXd w = p.weights();
  w[1] = -0.7071;
  try {
    igac::NurbsPatch(p.all_knots(), p.points(), w);
    ADD_FAILURE() << "a negative weight accepted";
  } catch (const igac::SplineError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("weight -0.7071"), std::string::npos) << msg;
    EXPECT_NE(msg.find("control point 1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("not positive"), std::string::npos) << msg;
  }
}

// ---------------------------------------------------------- a good run

TEST(BadInput, GoodRunWritesSummaryWithDesignKeys) {
  TempDir tmp("good");
  const fs::path out = tmp.path() / "out";
  const std::string c = std::string(IGAC_SOURCE_DIR) + "/cases/lame_cylinder.toml";
  const Outcome o = run_igac("run " + quote(c) + " --quiet --out " + quote(out.string()), tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(o.output, "") << "--quiet prints nothing";
  ASSERT_TRUE(fs::is_regular_file(out / "summary.json"));
  std::ifstream in(out / "summary.json");
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(in));
  for (const char* k : {"case", "dim", "degree", "elements", "dofs", "multipliers", "status", "load_steps", "timing_s"})
    EXPECT_TRUE(j.contains(k)) << "summary.json lacks '" << k << "'";
  EXPECT_EQ(j.value("case", ""), "lame_cylinder");
  EXPECT_EQ(j.value("dim", 0), 2);
  EXPECT_EQ(j.value("degree", 0), 2);
  EXPECT_EQ(j.value("elements", 0), 2 * 4 * 4);  // [2, 4] elements, refine = 1
  EXPECT_GT(j.value("dofs", 0), 0);
  EXPECT_EQ(j.value("multipliers", -1), 0);
  EXPECT_EQ(j.value("status", ""), "converged");
  ASSERT_TRUE(j["load_steps"].is_array());
  ASSERT_FALSE(j["load_steps"].empty());
  for (const auto& step : j["load_steps"])
    for (const char* k : {"load_factor", "newton_iterations", "residual_norms", "active_set_sizes"})
      EXPECT_TRUE(step.contains(k)) << "load step lacks '" << k << "'";
  EXPECT_DOUBLE_EQ(j["load_steps"].back().value("load_factor", 0.0), 1.0);
  ASSERT_TRUE(j["timing_s"].is_object());
  for (const char* k : {"assembly", "linear_solve", "total"}) {
    ASSERT_TRUE(j["timing_s"].contains(k)) << "timing_s lacks '" << k << "'";
    EXPECT_GE(j["timing_s"][k].get<double>(), 0.0);
  }
  EXPECT_GE(j["timing_s"]["total"].get<double>(), j["timing_s"]["assembly"].get<double>());
  // The Lame case has a closed form: errors are reported.
  ASSERT_TRUE(j.contains("errors"));
  EXPECT_GT(j["errors"].value("displacement_l2", 0.0), 0.0);
  // Nothing is left half-written (files are renamed into place).
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

}  // namespace
