// SPDX-License-Identifier: BSD-3-Clause
// Two deformable bodies in large deformation (contact/finite_strain_mortar):
// the Newton matrix against central differences of the residual in 2D and
// 3D with a curved master, the slave-master coupling that the stiffness
// pattern does not hold, and the contact force on the slave equal and
// opposite to the force on the master.
#include <gtest/gtest.h>

#include <algorithm>

#include "model/finite_strain_problem.hpp"
#include "engine/linear_static.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/central_differences.hpp"
#include "tests/support/newton_order.hpp"

using namespace igac;

namespace {

const std::string kData = std::string(IGAC_SOURCE_DIR) + "/tests/data/";

Model model_of(const std::string& file) {
  CaseSpec spec = read_case(kData + file);
  apply_overrides(spec, {}, 0);
  Model m = build_model(spec);
  return m;
}

// The problem of `file` solved to its full load; t of the last step.
double solve(const Model& m, FiniteStrainProblem& problem, Eigen::VectorXd& x) {
  x = Eigen::VectorXd::Zero(problem.size());
  problem.activate_nearest(x, int(free_rigid_modes(m.body, *m.dofs).modes.cols()));
  LoadSteppingOptions opt;
  opt.steps = m.spec.loading.steps;
  opt.quiet = true;
  const auto summary = run_load_steps(problem, x, opt, {});
  EXPECT_EQ(summary.status, "converged");
  return summary.steps.empty() ? 0.0 : summary.steps.back().load_factor;
}

void expect_tangent_matches(const std::string& file, int stride) {
  constexpr double kTolerance = 1e-5;  // relative to the column's largest entry
  const Model m = model_of(file);
  FiniteStrainProblem problem(finite_strain_setup(m));
  Eigen::VectorXd x;
  const double t = solve(m, problem, x);
  ASSERT_EQ(t, 1.0);
  const auto active = problem.active_set(t, x);
  ASSERT_GE(std::count(active.begin(), active.end(), 1), 3) << "the contact zone must be active";
  std::vector<int> columns;
  for (int j = 0; j < problem.size(); j += (j < problem.num_displacements() ? stride : 1)) columns.push_back(j);
  const int checked = igac_test::expect_jacobian_matches_central_differences(problem, t, x, columns, kTolerance);
  EXPECT_GT(checked, int(columns.size()) * 9 / 10);
}

}  // namespace

TEST(FiniteStrainTwoBodies, TangentMatchesCentralDifferences2D) {
  expect_tangent_matches("finite_strain_two_bodies.toml", 3);
}

TEST(FiniteStrainTwoBodies, TangentMatchesCentralDifferences3D) {
  expect_tangent_matches("finite_strain_two_bodies_3d.toml", 25);
}

TEST(FiniteStrainTwoBodies, SlaveMasterCouplingIsOutsideThePatternAndNotNegligible) {
  // The curvature terms couple the block's and the roller's control points,
  // which no element joins: they come as K_coupling, and they matter (the
  // tangent check above fails without them).
  const Model m = model_of("finite_strain_two_bodies.toml");
  FiniteStrainProblem problem(finite_strain_setup(m));
  Eigen::VectorXd x;
  const double t = solve(m, problem, x);
  BlockJacobian J;
  ASSERT_TRUE(problem.block_jacobian(t, x, J));
  // (K_coupling also holds the follower pressure's load stiffness, inside
  // K's pattern on the loaded face: the entries outside it are the coupling)
  double coupling = 0;
  int outside = 0;
  for (int c = 0; c < J.K_coupling.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(J.K_coupling, c); it; ++it)
      if (J.K.coeff(it.row(), it.col()) == 0.0) {
        ++outside;
        coupling = std::max(coupling, std::abs(it.value()));
      }
  ASSERT_GT(outside, 0);
  const double stiffness = Eigen::MatrixXd(J.K).cwiseAbs().maxCoeff();
  EXPECT_GT(coupling, 1e-4 * stiffness);
}

TEST(FiniteStrainTwoBodies, ForceOnTheSlaveIsMinusTheForceOnTheMaster) {
  // sum_K lambda_K dgamma_K/du summed per component over each body: the
  // basis functions of either side are a partition of unity at every point.
  constexpr double kRoundOff = 1e-12;
  for (const char* file : {"finite_strain_two_bodies.toml", "finite_strain_two_bodies_3d.toml"}) {
    const Model m = model_of(file);
    FiniteStrainProblem problem(finite_strain_setup(m));
    Eigen::VectorXd x;
    const double t = solve(m, problem, x);
    BlockJacobian J;
    ASSERT_TRUE(problem.block_jacobian(t, x, J));
    const Eigen::VectorXd f = J.B.transpose() * x.tail(problem.num_multipliers());
    const int dim = m.body.space_dim();
    const std::vector<int> part = m.body.parts();
    std::vector<int> patch_of_cp(size_t(m.body.num_control_points()), -1);
    for (int p = 0; p < m.body.num_patches(); ++p)
      for (int a : m.body.body_cps(p)) patch_of_cp[size_t(a)] = p;
    Eigen::MatrixXd per_body = Eigen::MatrixXd::Zero(2, dim);
    for (int i = 0; i < m.dofs->num_dofs(); ++i)
      if (m.dofs->equation(i) >= 0) per_body(part[patch_of_cp[i / dim]], i % dim) += f[m.dofs->equation(i)];
    // the vertical component (the other ones are partly held by symmetry)
    EXPECT_GT(std::abs(per_body(0, dim - 1)), 1e-4) << file;
    EXPECT_NEAR(per_body(0, dim - 1), -per_body(1, dim - 1), kRoundOff * std::abs(per_body(0, dim - 1))) << file;
  }
}

TEST(FiniteStrainTwoBodies, SwappingSlaveAndMasterGivesTheSameForce) {
  // The roller's curved face as the master, then as the slave: the contact
  // resultant balances the follower load in both (to the Newton
  // tolerance), and the two agree to the discretisation error (measured
  // 6.5e-5 on the vertical force, 0.3 % on the Cauchy peak at this mesh).
  constexpr double kBalance = 1e-8;
  constexpr double kForceDiscretisation = 1e-3;
  constexpr double kPeakDiscretisation = 0.02;
  std::vector<RunResult> runs;
  for (bool swap : {false, true}) {
    CaseSpec spec = read_case(kData + "finite_strain_two_bodies.toml");
    apply_overrides(spec, {}, 0);
    if (swap) std::swap(spec.contacts.at(0).face, spec.contacts.at(0).master);
    Model m = build_model(spec);
    runs.push_back(solve_model(m, quiet_run()));
    ASSERT_EQ(runs.back().status, "converged");
    const RunResult& r = runs.back();
    ASSERT_EQ(r.contacts.size(), 1u);
    EXPECT_NEAR(std::abs(r.contacts[0].resultant[1]), r.applied_force, kBalance * r.applied_force);
  }
  const ContactResult &a = runs[0].contacts[0], &b = runs[1].contacts[0];
  EXPECT_LT(a.resultant[1] * b.resultant[1], 0.0) << "on the block, then on the roller";
  EXPECT_NEAR(std::abs(a.resultant[1]), std::abs(b.resultant[1]), kForceDiscretisation * std::abs(a.resultant[1]));
  EXPECT_NEAR(a.max_pressure_cauchy, b.max_pressure_cauchy, kPeakDiscretisation * a.max_pressure_cauchy);
}

TEST(FiniteStrainTwoBodies, EachBodysReactionComesFromItsOwnLaw) {
  // The roller (E = 1) held sideways on x = 0, pressed by a dead vertical
  // load into the block (E = 3): its symmetry reaction balances the contact
  // force on it, -resultant (the resultant is the force on the slave, the
  // block).  With the block's law for both bodies the roller's reaction was
  // three times too large.
  constexpr double kBalance = 1e-7;
  CaseSpec spec = read_case(kData + "finite_strain_two_bodies.toml");
  apply_overrides(spec, {}, 0);
  spec.loading.follower_pressure = false;
  Model m = build_model(spec);
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  const FaceReaction* roller = nullptr;
  for (const FaceReaction& f : r.dirichlet_reactions)
    if (f.face == "roller:left") roller = &f;
  ASSERT_NE(roller, nullptr);
  const Eigen::VectorXd& on_block = r.contacts.at(0).resultant;
  ASSERT_GT(std::abs(on_block[0]), 1e-4);
  EXPECT_NEAR(roller->force[0], on_block[0], kBalance * std::abs(on_block[1]));
}

TEST(FiniteStrainTwoBodies, NewtonConvergesQuadraticallyOnceTheActiveSetSettles) {
  // the shipped pair at the paper's load: the consistent linearisation
  // (with the slave-master blocks GMRES applies) keeps Newton's order
  constexpr double kMinOrder = 1.8;
  CaseSpec spec = read_case(std::string(IGAC_SOURCE_DIR) + "/cases/roller_on_block_neohookean.toml");
  apply_overrides(spec, {}, 0);
  Model m = build_model(spec);
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  igac_test::expect_newton_order(r, kMinOrder, igac_test::kTwoBodyRoundOffFloor);
}

TEST(FiniteStrainTwoBodies, StatesVisitedBetweenChangeNothingAtTheSameState) {
  // Each contact keeps the mortar points of the last state (MortarPointCache):
  // a residual and a Jacobian at x asked after another state's residual are
  // those of a fresh problem at x, to the bit.
  for (const char* file : {"finite_strain_two_bodies.toml", "finite_strain_two_bodies_3d.toml"}) {
    const Model m = model_of(file);
    FiniteStrainProblem visited(finite_strain_setup(m)), fresh(finite_strain_setup(m));
    Eigen::VectorXd x;
    const double t = solve(m, visited, x);
    Eigen::VectorXd r_fresh, r_visited, r_other;
    BlockJacobian J_fresh, J_visited;
    ASSERT_TRUE(fresh.residual(t, x, r_fresh));
    ASSERT_TRUE(fresh.block_jacobian(t, x, J_fresh));
    Eigen::VectorXd other = x;
    const int n = visited.num_displacements();  // (not a translation: that would leave the cut as it is)
    other.head(n) += 1e-3 * Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
    ASSERT_TRUE(visited.residual(t, other, r_other));
    ASSERT_TRUE(visited.block_jacobian(t, x, J_visited));
    ASSERT_TRUE(visited.residual(t, x, r_visited));
    EXPECT_GT((r_other - r_fresh).norm(), 0.0) << file;
    EXPECT_EQ((r_visited - r_fresh).cwiseAbs().maxCoeff(), 0.0) << file;
    EXPECT_EQ(Eigen::MatrixXd(J_visited.K - J_fresh.K).cwiseAbs().maxCoeff(), 0.0) << file;
    EXPECT_EQ(Eigen::MatrixXd(J_visited.B - J_fresh.B).cwiseAbs().maxCoeff(), 0.0) << file;
    EXPECT_EQ(Eigen::MatrixXd(J_visited.K_coupling - J_fresh.K_coupling).cwiseAbs().maxCoeff(), 0.0) << file;
  }
}
