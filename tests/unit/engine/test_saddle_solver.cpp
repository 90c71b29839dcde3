// SPDX-License-Identifier: BSD-3-Clause
// The direct backend's iterative part (engine/saddle_solver.hpp) when its
// preconditioner is not J's inverse:
//  - a K_coupling the factor leaves out (a follower load's unsymmetric
//    stiffness) is absorbed by GMRES in a few iterations of one Krylov
//    space, with no LU fallback;
//  - a rigid motion that no active row holds (a body between frictionless
//    planes sliding along them) leaves J singular along it: the step is
//    one exact solution, the one that does not move the body along that
//    motion (its pinned equation keeps its value), found without an LU
//    of the singular J;
//  - a K_s that is indefinite (a soft mode made negative by stress) is
//    factorised with a shift at the equations whose pivot failed, and GMRES
//    absorbs the shift: no LU of J while a few shifts do; beyond
//    kMaxShifts of them, the LU of J, with the same answer.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/block_jacobian.hpp"
#include "engine/saddle_solver.hpp"

using namespace igac;

namespace {

// A chain of n springs of stiffness 1 + 0.01 i, no support: K R = 0 for
// the translation R = 1 / sqrt(n), entries from `first` on.
void add_free_chain(std::vector<Eigen::Triplet<double>>& t, int first, int n) {
  for (int i = 0; i + 1 < n; ++i) {
    const double k = 1.0 + 0.01 * i;
    const int a = first + i, b = first + i + 1;
    t.emplace_back(a, a, k), t.emplace_back(b, b, k), t.emplace_back(a, b, -k), t.emplace_back(b, a, -k);
  }
}

double relative_residual(const BlockJacobian& J, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  return (assemble_condensed(J) * x - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

}  // namespace

TEST(SaddleSolver, AnUnsymmetricCouplingIsAbsorbedByGmresWithoutFallback) {
  // One chain held at its first node by a stiff spring, two stops on it,
  // and a skew coupling between distant nodes (of K's size): the symmetric
  // factor preconditions J up to a rank-4 term, which a Krylov space of a
  // few vectors resolves; restarting it after every vector stalls.
  const int n = 30;
  std::vector<Eigen::Triplet<double>> t;
  add_free_chain(t, 0, n);
  t.emplace_back(0, 0, 5.0);
  BlockJacobian J;
  J.K.resize(n, n);
  J.K.setFromTriplets(t.begin(), t.end());
  Eigen::MatrixXd Kc = Eigen::MatrixXd::Zero(n, n);
  Kc(3, 25) = 0.8, Kc(25, 3) = -0.8, Kc(10, 20) = -0.6, Kc(20, 10) = 0.6;
  J.K_coupling = Kc.sparseView();
  J.B.resize(2, n);
  J.B.insert(0, 12) = 1.0;
  J.B.insert(1, 27) = 0.5, J.B.insert(1, 28) = 0.5;
  J.s = Eigen::Vector2d(3.0, 0.0);  // the first row active, the second inactive
  J.d = Eigen::Vector2d(0.0, 1.0);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n + 2, 1.0, -0.5);
  SaddleSolver solver;
  ASSERT_TRUE(solver.setup(J));
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.solve(b, x));
  EXPECT_EQ(solver.stats().fallbacks, 0);
  EXPECT_GT(solver.stats().krylov_iterations, 1);  // (the preconditioner alone is not the solve)
  EXPECT_LE(solver.stats().krylov_iterations, 8);
  EXPECT_LE(relative_residual(J, x, b), 1e-12);
}

TEST(SaddleSolver, AMotionNoActiveRowHoldsIsLeftAlone) {
  // Two free chains, each with its translation as a rigid mode pinned at
  // its first node; an active stop on the first chain only.  The load on
  // the second is self-equilibrated, so J x = b has solutions along the
  // second chain's translation: the solve returns the one whose pinned
  // node does not move.
  const int n = 12;
  std::vector<Eigen::Triplet<double>> t;
  add_free_chain(t, 0, n);
  add_free_chain(t, n, n);
  BlockJacobian J;
  J.K.resize(2 * n, 2 * n);
  J.K.setFromTriplets(t.begin(), t.end());
  J.rigid_modes = Eigen::MatrixXd::Zero(2 * n, 2);
  J.rigid_modes.col(0).head(n).setConstant(1 / std::sqrt(double(n)));
  J.rigid_modes.col(1).tail(n).setConstant(1 / std::sqrt(double(n)));
  J.pinned = {0, n};
  J.B.resize(1, 2 * n);
  J.B.insert(0, 5) = 0.75, J.B.insert(0, 6) = 0.25;
  J.s = Eigen::VectorXd::Constant(1, 2.0);
  J.d = Eigen::VectorXd::Zero(1);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(2 * n + 1);
  b.head(n) = Eigen::VectorXd::LinSpaced(n, 0.5, 1.5);  // pressed on the stop
  b[n + 2] = 1.0, b[2 * n - 1] = -1.0;                   // stretching the second chain
  b[2 * n] = 0.2;                                        // the stop's gap change
  SaddleSolver solver;
  ASSERT_TRUE(solver.setup(J));
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.solve(b, x));
  EXPECT_EQ(solver.stats().fallbacks, 0);
  EXPECT_LE(relative_residual(J, x, b), 1e-12);
  EXPECT_EQ(x[n], 0.0);                            // the free chain's pinned node
  EXPECT_GT(std::abs(x[2 * n - 1] - x[n + 2]), 0);  // it did stretch
  EXPECT_NEAR(x[2 * n], b.head(n).sum(), 1e-12 * b.head(n).sum());  // the stop holds the first chain's load
}

namespace {
// A chain of n springs held at its first node by a spring of 5 to the
// ground and pressed at its last node by an active stop, with the springs
// after the nodes in `negative` of stiffness -0.3 (softened by stress): K
// is indefinite, J (the stop holding the chain's end) is not singular.
BlockJacobian chain_with_negative_springs(int n, const std::vector<int>& negative) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i + 1 < n; ++i) {
    const bool soft = std::find(negative.begin(), negative.end(), i) != negative.end();
    const double k = soft ? -0.3 : 1.0 + 0.01 * i;
    t.emplace_back(i, i, k), t.emplace_back(i + 1, i + 1, k), t.emplace_back(i, i + 1, -k), t.emplace_back(i + 1, i, -k);
  }
  t.emplace_back(0, 0, 5.0);
  BlockJacobian J;
  J.K.resize(n, n);
  J.K.setFromTriplets(t.begin(), t.end());
  J.B.resize(1, n);
  J.B.insert(0, n - 1) = 1.0;
  J.s = Eigen::VectorXd::Constant(1, 2.0);
  J.d = Eigen::VectorXd::Zero(1);
  return J;
}
}  // namespace

TEST(SaddleSolver, AnIndefiniteStiffnessIsShiftedWhereItsPivotFailsAndGmresAbsorbsTheShift) {
  const int n = 30;
  const BlockJacobian J = chain_with_negative_springs(n, {14});
  ASSERT_LT(Eigen::MatrixXd(J.K).selfadjointView<Eigen::Lower>().eigenvalues().minCoeff(), 0.0);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n + 1, 1.0, -0.5);
  SaddleSolver solver;
  ASSERT_TRUE(solver.setup(J));
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.solve(b, x));
  EXPECT_EQ(solver.stats().fallbacks, 0);
  EXPECT_EQ(solver.stats().shifted, 1);
  EXPECT_LE(solver.stats().krylov_iterations, 10);
  EXPECT_LE(relative_residual(J, x, b), 1e-12);
  // kappa_1 of J itself (not of the shifted factor), against the dense one
  const Eigen::MatrixXd dense = Eigen::MatrixXd(assemble_condensed(J));
  const double kappa = dense.cwiseAbs().colwise().sum().maxCoeff() * dense.inverse().cwiseAbs().colwise().sum().maxCoeff();
  EXPECT_GT(solver.condition_estimate(), 0.3 * kappa);  // (an estimate: a lower bound, usually within 3x)
  EXPECT_LE(solver.condition_estimate(), kappa * (1 + 1e-8));
  // the next setup of the same matrix starts from the shift: no new failure
  ASSERT_TRUE(solver.setup(J));
  ASSERT_TRUE(solver.solve(b, x));
  EXPECT_EQ(solver.stats().fallbacks, 0);
  EXPECT_LE(relative_residual(J, x, b), 1e-12);
}

TEST(SaddleSolver, MoreNegativeModesThanShiftsTakeTheLuOfJ) {
  const int n = 60;
  std::vector<int> negative;
  for (int i = 2; i < n - 2; i += 5) negative.push_back(i);  // 12 negative springs, more than kMaxShifts
  const BlockJacobian J = chain_with_negative_springs(n, negative);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n + 1, 1.0, -0.5);
  SaddleSolver solver;
  ASSERT_TRUE(solver.setup(J));
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.solve(b, x));
  EXPECT_EQ(solver.stats().fallbacks, 1);
  EXPECT_EQ(solver.stats().shifted, 0);
  EXPECT_LE(relative_residual(J, x, b), 1e-12);
}

TEST(SaddleSolver, RowsThatCombineGapsAndMultipliersAreSolvedWithKsFactor) {
  // A free chain (its translation pinned at node 0) held by one active
  // stop (row 0) and two rows that combine, as Coulomb friction's slip rows
  // do: row 1 reads B rows 1 and 0 and multipliers 1, 0 and the inactive 3;
  // row 2 reads B row 3 (an inactive row's) and multipliers 2 and 0.  The
  // preconditioner is J's inverse (K symmetric, K R = 0): one GMRES
  // iteration, no LU of J, the dense solution to round-off.
  const int n = 24, m = 4;
  std::vector<Eigen::Triplet<double>> t;
  add_free_chain(t, 0, n);
  BlockJacobian J;
  J.K.resize(n, n);
  J.K.setFromTriplets(t.begin(), t.end());
  J.rigid_modes = Eigen::MatrixXd::Constant(n, 1, 1 / std::sqrt(double(n)));
  J.pinned = {0};
  J.B.resize(m, n);
  J.B.insert(0, 5) = 1.0;
  J.B.insert(1, 8) = 0.6, J.B.insert(1, 9) = 0.4;
  J.B.insert(2, 15) = 1.0;
  J.B.insert(3, 20) = 0.5, J.B.insert(3, 21) = 0.5;
  J.s = Eigen::Vector4d(2.0, 0.0, 0.0, 0.0);
  J.d = Eigen::Vector4d(0.0, 0.0, 0.0, 1.5);
  std::vector<Eigen::Triplet<double>> mb{{1, 1, 0.7}, {1, 0, -0.3}, {2, 3, 0.4}, {2, 2, 0.2}};
  std::vector<Eigen::Triplet<double>> ml{{1, 1, 0.5}, {1, 0, -0.25}, {1, 3, 0.3}, {2, 2, 0.9}, {2, 0, 0.2}};
  J.mixed_B.resize(m, m);
  J.mixed_B.setFromTriplets(mb.begin(), mb.end());
  J.mixed_lambda.resize(m, m);
  J.mixed_lambda.setFromTriplets(ml.begin(), ml.end());
  EXPECT_TRUE(J.closed_row(0) && J.closed_row(1) && J.closed_row(2) && !J.closed_row(3));
  // the condensed J against the block formula written out densely
  const Eigen::MatrixXd B(J.B);
  Eigen::MatrixXd whole = Eigen::MatrixXd::Zero(n + m, n + m);
  whole.topLeftCorner(n, n) = Eigen::MatrixXd(J.K);
  whole.topRightCorner(n, m) = B.transpose();
  whole.bottomLeftCorner(m, n) = (Eigen::MatrixXd(J.s.asDiagonal()) + Eigen::MatrixXd(J.mixed_B)) * B;
  whole.bottomRightCorner(m, m) = Eigen::MatrixXd(J.d.asDiagonal()) + Eigen::MatrixXd(J.mixed_lambda);
  EXPECT_LE((Eigen::MatrixXd(assemble_condensed(J)) - whole).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LE((Eigen::MatrixXd(as_one_block(J).K) - whole).cwiseAbs().maxCoeff(), 1e-15);
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n + m, 1.0, -0.5);
  b.head(n).array() -= b.head(n).mean() - 0.1;  // a net load the active stop carries
  SaddleSolver solver;
  ASSERT_TRUE(solver.setup(J));
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.solve(b, x));
  EXPECT_EQ(solver.stats().fallbacks, 0);
  EXPECT_LE(solver.stats().krylov_iterations, 1);
  const Eigen::VectorXd dense = whole.fullPivLu().solve(b);
  EXPECT_LE((x - dense).cwiseAbs().maxCoeff(), 1e-12 * dense.cwiseAbs().maxCoeff());
  EXPECT_LE(relative_residual(J, x, b), 1e-13);
}
