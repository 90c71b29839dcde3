// SPDX-License-Identifier: BSD-3-Clause
// The 1-norm condition estimate (engine/condition_estimate.hpp) against the
// exact kappa_1 of small matrices, computed from their dense inverse: the
// estimate is a lower bound (every value it takes is some ||A^-1 x||_1 with
// ||x||_1 = 1) and, on these matrices, within Higham's factor 3.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <limits>
#include <random>

#include "engine/cholesky.hpp"
#include "engine/condition_estimate.hpp"

namespace {

using namespace igac;

// A lower bound, up to the round-off of the solves that computed it and of
// the dense inverse it is compared with: both are accurate to about eps kappa.
constexpr double kSolveRoundOff = 10;
bool at_most(double estimate, double exact) {
  return estimate <= exact * (1 + kSolveRoundOff * std::numeric_limits<double>::epsilon() * exact);
}
// Higham, Accuracy and Stability of Numerical Algorithms, sec. 15.3: the
// estimate is rarely more than a factor 3 below ||A^-1||_1.
constexpr double kWithinFactor = 3;

double exact_kappa1(const Eigen::MatrixXd& A) { return norm1(A) * norm1(Eigen::MatrixXd(A.inverse())); }

// A random SPD matrix with eigenvalues spread over `decades`.
Eigen::MatrixXd random_spd(int n, double decades, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd G(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) G(i, j) = normal(gen);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(G);
  const Eigen::MatrixXd Q = qr.householderQ();
  Eigen::VectorXd eig(n);
  for (int i = 0; i < n; ++i) eig[i] = std::pow(10.0, decades * i / (n - 1));
  return Q * eig.asDiagonal() * Q.transpose();
}

TEST(ConditionEstimate, DiagonalMatrixIsExact) {
  Eigen::VectorXd d(5);
  d << 4, -0.5, 2e3, 1, 7;
  const Eigen::MatrixXd A = d.asDiagonal();
  const VectorSolve solve = [&](const Eigen::VectorXd& b) -> Eigen::VectorXd { return b.cwiseQuotient(d); };
  EXPECT_NEAR(norm1(A) * inverse_norm1_estimate(5, solve, solve), exact_kappa1(A), 1e-12 * exact_kappa1(A));
}

TEST(ConditionEstimate, RandomSymmetricMatricesWithinAFactorThree) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Eigen::MatrixXd A = random_spd(40, 1.0 + seed % 8, seed);
    const Eigen::LLT<Eigen::MatrixXd> llt(A);
    const VectorSolve solve = [&](const Eigen::VectorXd& b) -> Eigen::VectorXd { return llt.solve(b); };
    const double estimate = norm1(A) * inverse_norm1_estimate(40, solve, solve), exact = exact_kappa1(A);
    EXPECT_PRED2(at_most, estimate, exact) << "seed " << seed;
    EXPECT_GE(estimate, exact / kWithinFactor) << "seed " << seed;
  }
}

TEST(ConditionEstimate, UnsymmetricMatricesWithTheirTransposeSolve) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::MatrixXd A(30, 30);
    for (int i = 0; i < 30; ++i)
      for (int j = 0; j < 30; ++j) A(i, j) = u(gen);
    A.diagonal().array() += 3.0 * trial;  // from nearly singular to well conditioned
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
    const Eigen::PartialPivLU<Eigen::MatrixXd> lut(A.transpose());
    const VectorSolve solve = [&](const Eigen::VectorXd& b) -> Eigen::VectorXd { return lu.solve(b); };
    const VectorSolve solve_t = [&](const Eigen::VectorXd& b) -> Eigen::VectorXd { return lut.solve(b); };
    const double estimate = norm1(A) * inverse_norm1_estimate(30, solve, solve_t), exact = exact_kappa1(A);
    EXPECT_PRED2(at_most, estimate, exact) << "trial " << trial;
    EXPECT_GE(estimate, exact / kWithinFactor) << "trial " << trial;
  }
}

// The factor's estimate: the 1D Laplacian tridiag(-1, 2, -1), whose kappa_1
// grows as n^2 / 2, by CHOLMOD.
TEST(ConditionEstimate, SparseCholeskyOfTheLaplacian) {
  for (int n : {10, 100, 400}) {
    Eigen::SparseMatrix<double> A(n, n);
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < n; ++i) {
      t.emplace_back(i, i, 2.0);
      if (i > 0) t.emplace_back(i, i - 1, -1.0), t.emplace_back(i - 1, i, -1.0);
    }
    A.setFromTriplets(t.begin(), t.end());
    SparseCholesky chol;
    chol.factorize(A);
    const double estimate = chol.condition_estimate(), exact = exact_kappa1(Eigen::MatrixXd(A));
    EXPECT_PRED2(at_most, estimate, exact) << n;
    EXPECT_GE(estimate, exact / kWithinFactor) << n;
  }
}

}  // namespace
