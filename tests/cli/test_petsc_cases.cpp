// SPDX-License-Identifier: BSD-3-Clause
// Every shipped case on both linear backends (issue 36): `--solver petsc`
// on one process and under mpirun -n 2 (scripts/mpirun.sh) gives the
// direct solver's results, every number of summary.json and of the CSV
// files (pressure*.csv, load_curve.csv), by the rule of the golden records
// (tests/support/summary_compare.hpp): a MUMPS factorisation against
// CHOLMOD's, both backward stable, so the two agree to round-off times the
// direct run's condition estimate.  Counts (dofs, active sets, cut-backs,
// load steps) exactly; the Newton path of a load step (its iterations and
// residuals) is, as in the golden records, the way to the solution and not
// compared.  Only `solver` itself differs (its type, ranks, method).
//
// Large deformation runs every Newton step's linear solve in PETSc
// (solvers/petsc_newton.hpp); small deformation its active-set solve
// (solvers/petsc_contact.hpp).  The 3D Hertz cases run on a coarser mesh
// (their case's first `elements` replaced): their shipped meshes take a
// minute each in PETSc.  Small deformation with friction or along load curves
// solves its iterations and steps through the same linear backend as the
// Newton driver; the load-curve cases of tests/data join the shipped ones.
// Together about 5 minutes of CPU (sphere_on_block on its shipped mesh
// alone took 134 s: coarsened too).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/igac_process.hpp"
#include "tests/support/solve_tolerance.hpp"
#include "tests/support/summary_compare.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace igac_test::summary_compare;
using igac_test::quote;
using igac_test::run_mpi;

const fs::path kSource = IGAC_SOURCE_DIR;

#ifdef IGAC_WITH_PETSC
constexpr bool kHavePetsc = true;
#else
constexpr bool kHavePetsc = false;
#endif

// The 3D cases whose shipped mesh is replaced by a coarser one.
// (sphere_on_block: its sphere's; the block keeps its mesh)
const std::map<std::string, std::string> kCoarse = {{"hertz3d", "[8, 4, 8]"},
                                                     {"hertz3d_high_load", "[8, 4, 8]"},
                                                     {"hertz3d_p3", "[8, 2, 8]"},
                                                     {"sphere_on_block", "[8, 4, 8]"}};

// Beside the shipped cases, the test cases of small deformation along load
// curves (tests/data; the shipped ones along curves are large deformation
// but for cattaneo_mindlin_cycle): without contact, frictionless, with
// friction in 2D and 3D, and between two bodies.
const std::vector<std::string> kCurveCases = {"curve_block", "curve_contact", "curve_friction_block",
                                              "curve_friction_box", "curve_friction_two_blocks"};

std::vector<std::string> cases() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(kSource / "cases"))
    if (e.path().extension() == ".toml") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  names.insert(names.end(), kCurveCases.begin(), kCurveCases.end());
  return names;
}

// The case file to run: the shipped one (or the test's), or its coarse copy in `dir`.
fs::path case_file(const std::string& name, const fs::path& dir) {
  const bool test_case = std::find(kCurveCases.begin(), kCurveCases.end(), name) != kCurveCases.end();
  const fs::path shipped = kSource / (test_case ? "tests/data" : "cases") / (name + ".toml");
  const auto coarse = kCoarse.find(name);
  if (coarse == kCoarse.end()) return shipped;
  std::string s = igac_test::read_file(shipped);
  const auto at = s.find("elements = [");
  s.replace(at, s.find(']', at) - at + 1, "elements = " + coarse->second);
  const fs::path p = dir / (name + ".toml");
  std::ofstream(p) << s;
  return p;
}


// The PETSc run in `petsc` against the direct one in `direct`; an iterative
// solve leaves `iterative_tolerance` (relative) of the solution undecided
// (tests/support/solve_tolerance.hpp).
void expect_same_results(const fs::path& direct, const fs::path& petsc, int ranks, const std::string& what,
                         double iterative_tolerance = 0) {
  const json d = json::parse(igac_test::read_file(direct / "summary.json"));
  const json p = json::parse(igac_test::read_file(petsc / "summary.json"));
  EXPECT_EQ(p["solver"]["type"], "petsc") << what;
  EXPECT_EQ(p["solver"]["ranks"], ranks) << what;
  ASSERT_GT(igac_test::largest_condition_estimate(d), 1.0) << "the direct run reports its condition estimate";
  Rule rule{igac_test::solve_accuracy(d, p, iterative_tolerance), {}};
  const json record = without_machine_keys(d, {"solver"});
  collect_scales(record, "", rule.kind_scale);
  Tally t;
  compare(record, p, what + " summary.json", 0, rule, t);
  for (const auto& e : fs::directory_iterator(direct)) {
    const std::string f = e.path().filename().string();
    if (e.path().extension() == ".csv" && (f.starts_with("pressure") || f == "load_curve.csv"))
      compare_csv(csv_record(e.path()), petsc / f, rule, t);
  }
  EXPECT_GT(t.numbers, 10);
  std::printf("%s: condition estimate %.3g, relative tolerance %.3g; %d numbers compared (%d integers exactly); "
              "largest |diff| / tolerance %.3g (%s), CSV %.3g (%s)\n",
              what.c_str(), rule.accuracy.condition, rule.accuracy.relative(), t.numbers, t.exact, t.result.ratio,
              t.result.at.c_str(), t.csv.ratio, t.csv.at.c_str());
}

// A test over cases, skipped where igac was built without PETSc.
class WithPetsc : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (!kHavePetsc) GTEST_SKIP() << "igac built without PETSc";
  }
};

class PetscCase : public WithPetsc {};

TEST_P(PetscCase, SameResultsAsTheDirectSolverOnOneAndTwoProcesses) {
  const std::string name = GetParam();
  igac_test::TempDir tmp("petsc_" + name);
  const std::string c = quote(case_file(name, tmp.path()).string());
  for (const char* dir : {"direct", "one", "two"}) fs::create_directories(tmp.path() / dir);
  auto o = igac_test::run_igac("run " + c + " --quiet --out out", tmp.path() / "direct");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  o = igac_test::run_igac("run " + c + " --quiet --out out --solver petsc", tmp.path() / "one");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  expect_same_results(tmp.path() / "direct" / "out", tmp.path() / "one" / "out", 1, name + " on one process");
  o = run_mpi(2, "run " + c + " --quiet --out out --solver petsc", tmp.path() / "two");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  expect_same_results(tmp.path() / "direct" / "out", tmp.path() / "two" / "out", 2, name + " on two processes");
}

std::string case_name(const ::testing::TestParamInfo<std::string>& info) { return info.param; }
INSTANTIATE_TEST_SUITE_P(Shipped, PetscCase, ::testing::ValuesIn(cases()), case_name);

}  // namespace

namespace {

// A run stopped after step 3 by the direct solver and continued on PETSc
// (one process and two) ends where the direct run that never stopped ends:
// the state file holds no trace of the backend, and a restart takes the
// friction history (the slip, the stick/slip states) whichever solved it.
// Large deformation with friction (oring_friction) and small deformation
// with friction along a load curve (cattaneo_mindlin_cycle).
class PetscRestart : public WithPetsc {};

TEST_P(PetscRestart, ADirectRunContinuedOnPetscEndsWhereTheDirectRunEnds) {
  const std::string name = GetParam();
  igac_test::TempDir tmp("petsc_restart_" + name);
  const std::string c = quote((kSource / "cases" / (name + ".toml")).string());
  auto o = igac_test::run_igac("run " + c + " --quiet --out whole", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  for (const int processes : {1, 2}) {
    const std::string part = "part" + std::to_string(processes);
    o = igac_test::run_igac("run " + c + " --quiet --out " + part + " --stop-after-step 3", tmp.path());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    const std::string resume = "run " + c + " --quiet --out " + part + " --restart " + part + " --solver petsc";
    o = processes == 1 ? igac_test::run_igac(resume, tmp.path()) : run_mpi(2, resume, tmp.path());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    expect_same_results(tmp.path() / "whole", tmp.path() / part, processes,
                        name + " continued on " + std::to_string(processes) + " process(es)");
  }
}

INSTANTIATE_TEST_SUITE_P(Shipped, PetscRestart, ::testing::Values("oring_friction", "cattaneo_mindlin_cycle"),
                         case_name);

}  // namespace

namespace {

// A misspelt PETSc option on each route of the linear backend (the Newton
// steps of large deformation, small-deformation friction, a load curve):
// the error line last, naming it, exit 2, nothing written.  The run's header
// waits for the first solve, which reads the options, but no longer than
// the heartbeat's period (a line at least every 5 s): on a loaded machine
// the header may come first, and then it is the header's lines alone
// (`igac: <name> ...`, indented lines), not a step or a result.
TEST(PetscBackend, AMisspeltOptionIsOneErrorLineOnEveryRoute) {
  if (!kHavePetsc) GTEST_SKIP() << "igac built without PETSc";
  for (const char* name : {"oring", "cattaneo_mindlin", "cattaneo_mindlin_cycle"}) {
    igac_test::TempDir tmp("petsc_option");
    const std::string c = quote((kSource / "cases" / (std::string(name) + ".toml")).string());
    const auto o =
        igac_test::run_igac("run " + c + " --out out --solver petsc --petsc-options '-ksp_tpye cg'", tmp.path());
    EXPECT_EQ(o.exit_code, 2) << name << ": " << o.output;
    const std::string error = "igac: error: " + (kSource / "cases" / (std::string(name) + ".toml")).string() +
                              ": [solver] options: PETSc option -ksp_tpye was not used by the solver (misspelt, or "
                              "an option of another solver type)\n";
    ASSERT_TRUE(o.output.ends_with(error)) << name << ": " << o.output;
    std::istringstream before(o.output.substr(0, o.output.size() - error.size()));
    for (std::string line; std::getline(before, line);)
      EXPECT_TRUE(line.starts_with("igac: " + std::string(name) + " ") || line.starts_with("  "))
          << name << ": a line before the error that is not the header's: " << line;
    EXPECT_EQ(o.output.find("step "), std::string::npos) << name << ": " << o.output;
    EXPECT_FALSE(fs::exists(tmp.path() / "out")) << name;
  }
}

}  // namespace

namespace {

// The largest |R|/F at the end of any load step of a run (0: none, a
// small-deformation run without steps).
double largest_final_residual(const fs::path& run) {
  const json s = json::parse(igac_test::read_file(run / "summary.json"));
  double largest = 0;
  if (s.contains("load_steps"))
    for (const json& step : s["load_steps"])
      if (!step["residual_norms"].empty()) largest = std::max(largest, step["residual_norms"].back().get<double>());
  return largest;
}

// The relative tolerance of the small-deformation active set's Krylov
// solves without the spline multigrid (kTight in solvers/petsc_contact.cpp):
// what a run without Newton steps leaves undecided.
constexpr double kActiveSetKrylovTolerance = 1e-11;

// A multigrid's runs (`preconditioner`, with `extra` arguments) against the
// direct solver's, on one process and two: the same results to what the
// iterative solves leave undecided: the final Newton residual (the larger of
// the two runs) times the condition estimate, or the active-set solve's
// Krylov tolerance (small deformation).
void expect_multigrid_matches_direct(const std::string& name, const fs::path& case_path, const std::string& extra,
                                     const std::string& preconditioner) {
  igac_test::TempDir tmp("petsc_" + preconditioner + "_" + name);
  const std::string c = quote(case_path.string()) + extra;
  auto o = igac_test::run_igac("run " + c + " --quiet --out direct", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  for (const int ranks : {1, 2}) {
    const std::string out = "mg" + std::to_string(ranks);
    const std::string args = "run " + c + " --quiet --out " + out + " --solver petsc --preconditioner " + preconditioner;
    o = ranks == 1 ? igac_test::run_igac(args, tmp.path()) : run_mpi(2, args, tmp.path());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    const json p = json::parse(igac_test::read_file(tmp.path() / out / "summary.json"));
    EXPECT_TRUE(p["solver"]["method"].get<std::string>().starts_with("fgmres + ")) << p["solver"]["method"];
    EXPECT_FALSE(p["solver"]["krylov_iterations"].empty());
    const double newton = std::max(largest_final_residual(tmp.path() / "direct"), largest_final_residual(tmp.path() / out));
    expect_same_results(tmp.path() / "direct", tmp.path() / out, ranks,
                        name + " with " + preconditioner + " on " + std::to_string(ranks) + " process(es)",
                        newton > 0 ? newton : kActiveSetKrylovTolerance);
  }
}

// `preconditioner = "algebraic_multigrid"` (FGMRES, a Schur field split,
// GAMG on the displacements) on every route it serves: the Newton steps of
// large deformation with a body held by contact alone and a follower load
// (hertz3d_neohookean: the augmented Lagrangian makes the displacement
// block definite), in the symmetric form (oring), between two bodies
// (roller_on_block_neohookean), the small-deformation active set
// (hertz2d, kActiveSetKrylovTolerance) and a solve without multipliers
// (lame_cylinder: the whole matrix is the displacement field).
class PetscAlgebraicMultigrid : public WithPetsc {};

TEST_P(PetscAlgebraicMultigrid, SameResultsAsTheDirectSolverOnOneAndTwoProcesses) {
  const std::string name = GetParam();
  expect_multigrid_matches_direct(name, kSource / "cases" / (name + ".toml"), "", "algebraic_multigrid");
}

INSTANTIATE_TEST_SUITE_P(Shipped, PetscAlgebraicMultigrid,
                         ::testing::Values("hertz3d_neohookean", "oring", "roller_on_block_neohookean", "hertz2d",
                                           "lame_cylinder"),
                         case_name);

// `preconditioner = "spline_multigrid"` on the Newton steps of large
// deformation (the active set's own route is tested in test_petsc.cpp), one
// refinement above the shipped mesh so that the hierarchy has two levels:
// a follower load on a body held by contact alone (hertz3d_neohookean, on
// a coarser mesh: [6, 2, 6] refined once), the symmetric form (oring), two
// bodies with the curvature coupling outside K (roller_on_block_neohookean)
// and the mixed formulation's condensed matrix (oring_rubber).
class PetscSplineMultigridNewton : public WithPetsc {};

TEST_P(PetscSplineMultigridNewton, SameResultsAsTheDirectSolverOnOneAndTwoProcesses) {
  const std::string name = GetParam();
  igac_test::TempDir tmp("coarse_" + name);
  fs::path path = kSource / "cases" / (name + ".toml");
  if (name == "hertz3d_neohookean") {
    std::string s = igac_test::read_file(path);
    const auto at = s.find("elements = [");
    s.replace(at, s.find(']', at) - at + 1, "elements = [6, 2, 6]");
    path = tmp.path() / (name + ".toml");
    std::ofstream(path) << s;
  }
  expect_multigrid_matches_direct(name, path, " --refine 1", "spline_multigrid");
}

INSTANTIATE_TEST_SUITE_P(Shipped, PetscSplineMultigridNewton,
                         ::testing::Values("hertz3d_neohookean", "oring", "roller_on_block_neohookean", "oring_rubber"),
                         case_name);

// Friction and ties solve their multipliers in one block with the
// displacements: the field split has no fields there, and says so in one
// line (either kinematics), nothing written.
TEST(PetscAlgebraicMultigrid, FrictionIsRefusedInOneLine) {
  if (!kHavePetsc) GTEST_SKIP() << "igac built without PETSc";
  for (const char* name : {"oring_friction", "cattaneo_mindlin"}) {
    igac_test::TempDir tmp("petsc_amg_friction");
    const std::string path = (kSource / "cases" / (std::string(name) + ".toml")).string();
    const auto o = igac_test::run_igac(
        "run " + quote(path) + " --out out --solver petsc --preconditioner algebraic_multigrid", tmp.path());
    EXPECT_EQ(o.exit_code, 2) << name << ": " << o.output;
    EXPECT_TRUE(o.output.starts_with("igac: error: --preconditioner algebraic_multigrid") ||
                o.output.starts_with("igac: error: " + path))
        << o.output;
    EXPECT_NE(o.output.find("needs the multipliers apart from the displacements"), std::string::npos) << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
    EXPECT_FALSE(fs::exists(tmp.path() / "out")) << name;
  }
}

}  // namespace
