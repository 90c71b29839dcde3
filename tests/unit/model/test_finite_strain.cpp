// SPDX-License-Identifier: BSD-3-Clause
// Large deformation: the full Newton tangent (total Lagrangian + follower
// pressure + contact with a curved obstacle) against central differences of
// the residual, quadratic convergence once the active set settles, the
// small-load limit (Neo-Hookean reproduces linear Hertz), the shipped cases,
// and the load-stepping driver's failure path (clear status, no NaN).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "model/finite_strain_problem.hpp"
#include "engine/linear_static.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/central_differences.hpp"
#include "tests/support/newton_order.hpp"

using namespace igac;

namespace {

const std::string kSource = IGAC_SOURCE_DIR;

Model model_of(const std::string& path, int refine = 0) {
  CaseSpec spec = read_case(path);
  apply_overrides(spec, {}, refine);
  Model m = build_model(spec);
  return m;
}

FiniteStrainSetup setup_of(const Model& m) { return finite_strain_setup(m); }

}  // namespace

TEST(FiniteStrainTangent, MatchesCentralDifferencesWithActiveCurvedContact) {
  constexpr double kTolerance = 1e-5;  // relative to the column's largest entry
  const Model m = model_of(kSource + "/tests/data/finite_strain_curved_obstacle.toml");
  FiniteStrainProblem problem(setup_of(m));
  double t = 0;
  const Eigen::VectorXd x = igac_test::converged_state(problem, &t, 4, 0.25);
  const auto active = problem.active_set(t, x);
  ASSERT_GE(std::count(active.begin(), active.end(), 1), 3) << "the contact zone must be active";
  // every multiplier column and displacement columns near the contact face
  std::vector<int> columns;
  for (int j = 0; j < problem.size(); j += (j < problem.num_displacements() ? 7 : 1)) columns.push_back(j);
  const int checked = igac_test::expect_jacobian_matches_central_differences(problem, t, x, columns, kTolerance);
  EXPECT_GT(checked, int(columns.size()) * 9 / 10);
}

TEST(FiniteStrainTangent, ChecksCanFail) {
  // The same comparison with the curvature term of the gap dropped (a plane's
  // zero dn/dx given to a curved obstacle) must fail: the check has teeth.
  const Model m = model_of(kSource + "/tests/data/finite_strain_curved_obstacle.toml");
  FiniteStrainSetup wrong = setup_of(m);
  const RigidPlane tangent_plane(Eigen::Vector2d(0, -1), Eigen::Vector2d(0, 1));
  FiniteStrainProblem right_problem(setup_of(m));
  Eigen::VectorXd x = Eigen::VectorXd::Zero(right_problem.size());
  right_problem.activate_nearest(x, 1);
  LoadSteppingOptions opt;
  opt.quiet = true;
  opt.steps = 4;
  ASSERT_EQ(run_load_steps(right_problem, x, opt, {}).status, "converged");
  Eigen::SparseMatrix<double> J_right, J_plane;
  ASSERT_TRUE(right_problem.jacobian(1.0, x, J_right));
  wrong.contacts.at(0).obstacle = &tangent_plane;
  FiniteStrainProblem plane_problem(wrong);
  ASSERT_TRUE(plane_problem.jacobian(1.0, x, J_plane));
  // the displacement block differs by the curvature term of the sphere
  const double diff = (Eigen::MatrixXd(J_right) - Eigen::MatrixXd(J_plane)).topLeftCorner(right_problem.num_displacements(), right_problem.num_displacements()).cwiseAbs().maxCoeff();
  EXPECT_GT(diff, 1e-6);
}

TEST(FiniteStrainNewton, ConvergesQuadraticallyOnceTheActiveSetSettles) {
  constexpr double kMinOrder = 1.8;
  Model m = model_of(kSource + "/cases/hertz2d_neohookean_pressure_study.toml", 1);
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  igac_test::expect_newton_order(r, kMinOrder);
}

TEST(FiniteStrainHertz, NeoHookeanAtSmallLoadReproducesLinearHertz) {
  // At P = 0.003 strains are ~1e-2: Neo-Hookean and linear elasticity agree
  // to that order.  Measured at a01e0b0: Neo-Hookean / linear peak 0.99200,
  // half width 1.00807 (the half width moves by whole spans of the contact
  // edge); 1 % leaves a margin of 1.2.  Neo-Hookean peak / Hertz p0 0.99016:
  // 1.5 % (was 2 %), a margin of 1.5.
  constexpr double kTolerance = 0.01, kHertzTolerance = 0.015;
  CaseSpec lin = read_case(kSource + "/cases/hertz2d.toml");
  CaseSpec nh = lin;
  nh.model = "neo_hookean";
  nh.loading.steps = 2;
  nh.loading.follower_pressure = false;  // the linear case's load is dead
  Model ml = build_model(lin), mn = build_model(nh);
  const RunResult rl = solve_model(ml), rn = solve_model(mn, quiet_run());
  ASSERT_EQ(rn.status, "converged");
  std::printf("Neo-Hookean / linear: peak %.6f, half width %.6f; Neo-Hookean peak / Hertz %.6f\n",
              rn.contacts.front().report.max_pressure / rl.contacts.front().report.max_pressure,
              rn.contacts.front().report.half_width / rl.contacts.front().report.half_width, rn.contacts.front().report.max_pressure / 0.045812);
  EXPECT_NEAR(rn.contacts.front().report.max_pressure / rl.contacts.front().report.max_pressure, 1.0, kTolerance);
  EXPECT_NEAR(rn.contacts.front().report.half_width / rl.contacts.front().report.half_width, 1.0, kTolerance);
  // and against Hertz (the linear values have their own test, test_hertz)
  EXPECT_NEAR(rn.contacts.front().report.max_pressure / 0.045812, 1.0, kHertzTolerance);
}

TEST(FiniteStrainCases, ShippedCasesConvergeWithBalancedForces) {
  // Total contact force = the follower load's resultant.  Measured 3.0e-13
  // relative (the pressure case: the last Newton step lands at round-off);
  // the bound is what Newton's stop (|R|_inf <= 1e-9 of the force scale)
  // guarantees summed over the ~100 loaded dofs: 1e-7.
  constexpr double kForceTolerance = 1e-7;
  // Newton's work, measured at a01e0b0 (steps: iterations):
  //   pressure      8 steps: 9 6 6 5 6 6 6 5 = 49, no cut-back
  //   displacement  7 steps: 6 6 5 6 5 5 5 = 38, no cut-back
  // Bounds with a margin: at most 12 iterations in a step (the first step's 9
  // + 3; quadratic convergence takes 5-6, a tangent that lost a term
  // converges linearly and needs more), no cut-back, and the total within
  // 20 % of the measured one.  (Every step's count <= max_newton_iterations
  // = 30, the former check, holds for any converged run.)
  constexpr int kMaxPerStep = 12;
  struct Shipped {
    const char* name;
    int total_iterations;
  };
  for (const Shipped& c : {Shipped{"hertz2d_neohookean_pressure", 49}, Shipped{"hertz2d_neohookean_displacement", 38}}) {
    const char* name = c.name;
    Model m = model_of(kSource + "/cases/" + name + ".toml");
    const RunResult r = solve_model(m, quiet_run());
    EXPECT_EQ(r.status, "converged") << name;
    ASSERT_TRUE(r.contact) << name;
    EXPECT_TRUE(r.u.allFinite()) << name;
    EXPECT_GT(r.contacts.front().report.active, 10) << name;
    if (r.applied_force > 0) {
      EXPECT_NEAR(r.contacts.front().report.total_force / r.applied_force, 1.0, kForceTolerance) << name;
    }
    int total = 0;
    for (const auto& st : r.load_steps->steps) {
      EXPECT_LE(st.newton_iterations, kMaxPerStep) << name << ", step at t = " << st.load_factor;
      EXPECT_EQ(st.cut_backs, 0) << name << ", step at t = " << st.load_factor;
      total += st.newton_iterations;
    }
    EXPECT_LE(total, 1.2 * c.total_iterations) << name;
    EXPECT_EQ(r.load_curve.size(), r.load_steps->steps.size());
  }
}

// GetFEM's converged values of the two paper 4.3 cases (README.md, "Large
// deformation (Neo-Hookean, paper 4.3)": 6 digits for force and peak, 4 for
// the half width; GetFEM's own scripts are not in this repository).
// Tolerances from the values measured at a01e0b0 (tests/data/golden), with a
// margin of about 2.5 above the larger of the two cases:
//  - contact force: measured +3.4e-6 and +4.1e-5 relative -> 1e-4 (was 0.5 %);
//  - nominal peak pressure: -0.0030 % and -0.0036 % -> 0.01 % (was 3 %);
//  - deformed half width, read from the discrete contact edge and so
//    bracketed by the span there: +0.024 % (pressure) -> 0.06 %, and -0.44 %
//    (displacement, where the edge sits in a coarser span) -> 0.6 % (both
//    were 3 %; the margin is 1.4 there, as the edge moves by whole spans).
TEST(FiniteStrainCases, ShippedCasesMatchGetFemConvergedValues) {
  constexpr double kForce = 1e-4, kPeak = 1e-4;
  struct Converged {
    const char* name;
    double force, half_width, max_pressure;
    double half_width_tolerance;
  };
  for (const Converged& c : {Converged{"hertz2d_neohookean_pressure", 0.111476, 0.4959, 0.238557, 6e-4},
                             Converged{"hertz2d_neohookean_displacement", 0.366592, 0.7673, 0.570388, 6e-3}}) {
    Model m = model_of(kSource + "/cases/" + c.name + ".toml");
    const RunResult r = solve_model(m, quiet_run());
    ASSERT_EQ(r.status, "converged") << c.name;
    EXPECT_NEAR(r.contacts.front().report.total_force, c.force, kForce * c.force) << c.name;
    EXPECT_NEAR(r.contacts.front().half_width_deformed, c.half_width, c.half_width_tolerance * c.half_width) << c.name;
    EXPECT_NEAR(r.contacts.front().report.max_pressure, c.max_pressure, kPeak * c.max_pressure) << c.name;
  }
}

TEST(FiniteStrainDriver, GivesUpWithAClearStatusAndNoNaN) {
  // One Newton iteration per step cannot converge the contact problem: the
  // driver must cut back down to the minimum increment and stop cleanly.
  CaseSpec spec = read_case(kSource + "/cases/hertz2d_neohookean_pressure_study.toml");
  spec.loading.max_newton_iterations = 1;
  spec.loading.min_increment = 0.02;
  Model m = build_model(spec);
  const RunResult r = solve_model(m, quiet_run());
  EXPECT_NE(r.status, "converged");
  EXPECT_NE(r.status.text().find("stopped at load factor"), std::string::npos) << r.status;
  EXPECT_TRUE(r.u.allFinite());
}

TEST(FiniteStrainDriver, MaxIncrementCapsTheGrowthOfFastSteps) {
  // Fast steps grow the increment by 1.5; [loading] max_increment caps it,
  // so steps = 20 with max_increment = 0.05 takes exactly 20 steps.
  CaseSpec spec = read_case(kSource + "/cases/hertz2d_neohookean_pressure_study.toml");
  spec.loading.steps = 20;
  spec.loading.max_increment = 0.05;
  Model m = build_model(spec);
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  EXPECT_EQ(r.load_steps->steps.size(), 20u);
  for (const auto& st : r.load_steps->steps) EXPECT_EQ(st.cut_backs, 0);
}

TEST(FiniteStrainDriver, TangentPredictorSavesTheFirstStepsCutBacks) {
  // u_y = -0.4 at once: from u = 0 the first step inverts the elements next
  // to the moved face and is cut back; the tangent predictor starts it from
  // x - J^{-1} dR/dt dt instead.  Same converged solution either way.
  CaseSpec spec = read_case(kSource + "/cases/hertz2d_neohookean_displacement.toml");
  spec.loading.tangent_predictor = false;
  Model plain = build_model(spec);
  spec.loading.tangent_predictor = true;
  Model predicted = build_model(spec);
  const RunResult rp = solve_model(plain, quiet_run()), rt = solve_model(predicted, quiet_run());
  ASSERT_EQ(rp.status, "converged");
  ASSERT_EQ(rt.status, "converged");
  int cuts_plain = 0, cuts_predicted = 0;
  for (const auto& st : rp.load_steps->steps) cuts_plain += st.cut_backs;
  for (const auto& st : rt.load_steps->steps) cuts_predicted += st.cut_backs;
  EXPECT_GT(cuts_plain, 0) << "the case is one that needs it";
  EXPECT_EQ(cuts_predicted, 0);
  EXPECT_NEAR(rt.contacts.front().report.total_force / rp.contacts.front().report.total_force, 1.0, 1e-7);
  EXPECT_LE((rt.u - rp.u).cwiseAbs().maxCoeff(), 1e-7 * rp.u.cwiseAbs().maxCoeff());
}
