// SPDX-License-Identifier: BSD-3-Clause
// The u-p Newton of the mixed formulation (model/finite_strain_problem.hpp,
// docs/design.md "Nearly incompressible solids"): every pressure block's
// dilatation theta_b (2 x 2 elements; the leftover of an odd direction in
// the last block) is an unknown of the iteration, condensed block by block in
// the linear solve (BlockJacobian::local).
//  - the whole Newton matrix, the block rows and columns included, against
//    central differences of the residual, at a state where theta_b is not
//    Pi_b J (the block pressure U'(theta_b) off the condensed one), with
//    contact active on a curved obstacle and a law whose U is not quadratic,
//    on a mesh of 15 x 4 elements: blocks of 2 x 2 and of 3 x 2;
//  - Newton converges quadratically in u and theta (the recorded norm is the
//    largest weighted row of both);
//  - the converged state solves the condensed problem too: today's residual
//    (theta_e = Pi_e J) at the same displacements is below the tolerance;
//  - with friction (the Newton matrix factorised whole, the block rows
//    still condensed) the same case converges, quadratically;
//  - a restart from a state without the block dilatations (a state file
//    written before them) is refused in one line.
#include <gtest/gtest.h>

#include <cmath>

#include "model/finite_strain_problem.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/central_differences.hpp"
#include "tests/support/newton_order.hpp"

namespace igac {
namespace {

// The curved-obstacle test case (quarter disc on a sphere, Neo-Hookean,
// follower pressure) in the mixed formulation at K/mu = 5000; `elements`:
// the mesh's elements per direction (empty: the case's 16 x 4).
Model mixed_model(double friction = 0, std::vector<int> elements = {}) {
  CaseSpec spec = read_case(IGAC_SOURCE_DIR "/tests/data/finite_strain_curved_obstacle.toml");
  if (!elements.empty()) spec.elements = elements;
  const double nu = 0.4999;
  spec.nu = nu;
  spec.material_parameters = {spec.E, nu, {}};
  spec.formulation = Formulation::mixed;
  spec.write_vtk = false;
  spec.contacts.at(0).friction = friction;
  apply_overrides(spec, {}, 0);
  Model m = build_model(spec);
  return m;
}

TEST(UpNewton, TangentWithBlockDilatationsMatchesCentralDifferences) {
  constexpr double kTolerance = 1e-5;  // relative to the column's largest entry
  const Model m = mixed_model(0, {15, 4});  // blocks of 2 x 2, the last along u of 3 x 2
  FiniteStrainProblem problem(finite_strain_setup(m));
  const int n = problem.num_displacements(), nz = problem.num_local();
  ASSERT_EQ(m.body.num_elements(), 60);
  // one dilatation per pressure function, after the multipliers: linear
  // C^0 (p = 2) on 7 x 2 spans (the last along u of 3 elements)
  ASSERT_EQ(nz, (7 + 1) * (2 + 1));
  const PressureSpace& space = problem.assembler().pressure_space();
  int of_three = 0;
  for (int a = 0; a < space.num_functions(); ++a) of_three += space.support_end(a) - space.support_begin(a) == 3 * 2;
  ASSERT_GT(of_three, 0) << "supports reach the span of 3 elements";
  ASSERT_EQ(problem.size(), n + problem.num_multipliers() + nz);
  double t = 0;
  Eigen::VectorXd x = igac_test::converged_state(problem, &t, 4, 0.25);
  const auto active = problem.active_set(t, x);
  ASSERT_GE(std::count(active.begin(), active.end(), 1), 3) << "the contact zone must be active";
  // theta_b moved off Pi_b J: the block rows' residuals are not zero
  for (int e = 0; e < nz; ++e) x[x.size() - nz + e] += 1e-4 * std::sin(3.0 * e + 1);
  Eigen::VectorXd r;
  ASSERT_TRUE(problem.residual(t, x, r));
  EXPECT_GT(r.tail(nz).cwiseAbs().maxCoeff(), 1e-7);
  std::vector<int> columns;
  for (int j = 0; j < problem.size(); j += (j < n ? 7 : 1)) columns.push_back(j);
  const int checked = igac_test::expect_jacobian_matches_central_differences(problem, t, x, columns, kTolerance);
  EXPECT_GT(checked, int(columns.size()) * 9 / 10);
}

TEST(UpNewton, ConvergesQuadraticallyToTheCondensedSolution) {
  const Model m = mixed_model();
  const RunResult run = solve_model(m, quiet_run());
  ASSERT_EQ(run.status, "converged");
  igac_test::expect_newton_order(run, 1.8);

  // The same steps by the driver, then the condensed formulation's residual
  // at the converged displacements: theta_b = Pi_b J, the pressure U'(Pi_b J).
  FiniteStrainProblem problem(finite_strain_setup(m));
  const int nz = problem.num_local();
  double t = 0;
  const Eigen::VectorXd x = igac_test::converged_state(problem, &t, m.spec.loading.steps);
  const double scale = problem.force_scale(t, x);
  Eigen::VectorXd r;
  ASSERT_TRUE(problem.residual(t, x, r));
  const Eigen::VectorXd w = problem.residual_weights();
  ASSERT_EQ(w.size(), r.size());
  EXPECT_LT(r.cwiseAbs().cwiseProduct(w).maxCoeff() / scale, 1e-9);  // u and theta rows converged
  Eigen::VectorXd dil;
  ASSERT_TRUE(problem.assembler().volume_changes(problem.displacement(t, x), dil));
  Eigen::VectorXd x_condensed = x;
  x_condensed.tail(nz) = dil;  // theta_b = Pi_b J: the displacement-only residual
  Eigen::VectorXd r_condensed;
  ASSERT_TRUE(problem.residual(t, x_condensed, r_condensed));
  EXPECT_EQ(r_condensed.tail(nz).cwiseAbs().maxCoeff(), 0.0);
  const double condensed = r_condensed.head(problem.num_displacements()).cwiseAbs().maxCoeff() / scale;
  std::cout << "  u-p Newton: condensed residual at its solution " << condensed << " (tolerance 1e-9)\n";
  EXPECT_LT(condensed, 2e-9);
}

TEST(UpNewton, ConvergesWithFriction) {
  const Model m = mixed_model(0.3);
  const RunResult run = solve_model(m, quiet_run());
  ASSERT_EQ(run.status, "converged");
  for (const auto& st : run.load_steps->steps) EXPECT_EQ(st.cut_backs, 0) << "step at t = " << st.load_factor;
  igac_test::expect_newton_order(run, 1.8);
}

TEST(UpNewton, RestartFromAStateWithoutTheDilatationsIsRefused) {
  Model m = mixed_model();
  FiniteStrainProblem problem(finite_strain_setup(m));
  StepState old;
  old.step = 1;
  old.driver.t = old.driver.dt = 0.25;
  old.driver.x = old.driver.x_old = Eigen::VectorXd::Zero(problem.size() - problem.num_local());
  RunControl control = quiet_run();
  control.resume = {old};
  try {
    solve_model(m, control);
    ADD_FAILURE() << "a state of the wrong size was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("the state file holds " + std::to_string(old.driver.x.size()) + " unknowns, this run has " +
                        std::to_string(problem.size())),
              std::string::npos)
        << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace igac
