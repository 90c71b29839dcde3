// SPDX-License-Identifier: BSD-3-Clause
#include "engine/condition_estimate.hpp"

#include <cmath>

namespace igac {

namespace {

Eigen::VectorXd signs(const Eigen::VectorXd& y) {
  return y.unaryExpr([](double v) { return v >= 0 ? 1.0 : -1.0; });
}

}  // namespace

double inverse_norm1_estimate(int n, const VectorSolve& solve, const VectorSolve& solve_transpose) {
  if (n == 0) return 0;
  constexpr int kMaxSteps = 5;  // LAPACK's ITMAX
  Eigen::VectorXd y = solve(Eigen::VectorXd::Constant(n, 1.0 / n));
  double estimate = y.lpNorm<1>();
  if (n == 1) return estimate;
  // z = A^-T sign(y) is a subgradient of ||A^-1 x||_1; the vertex e_j with the
  // largest |z_j| is the steepest ascent.  Climb while the estimate rises,
  // the sign pattern changes and the steepest vertex moves.
  Eigen::VectorXd xi = signs(y);
  Eigen::VectorXd z = solve_transpose(xi);
  Eigen::Index j = 0;
  z.cwiseAbs().maxCoeff(&j);
  for (int step = 1; step <= kMaxSteps; ++step) {
    y = solve(Eigen::VectorXd::Unit(n, j));
    const double previous = estimate;
    estimate = std::max(estimate, y.lpNorm<1>());
    const Eigen::VectorXd xi_next = signs(y);
    if (xi_next == xi || y.lpNorm<1>() <= previous) break;
    xi = xi_next;
    z = solve_transpose(xi);
    const Eigen::Index last = j;
    z.cwiseAbs().maxCoeff(&j);
    if (std::abs(z[last]) == std::abs(z[j])) break;
  }
  // Higham's safeguard: b_i = (-1)^i (1 + i / (n - 1)) catches matrices on
  // which the climb stalls (LAPACK's last step).
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = (i % 2 ? -1.0 : 1.0) * (1.0 + double(i) / (n - 1));
  return std::max(estimate, 2.0 * solve(b).lpNorm<1>() / (3.0 * n));
}

double norm1(const Eigen::SparseMatrix<double>& A) {
  double best = 0;
  for (int c = 0; c < A.outerSize(); ++c) {
    double s = 0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) s += std::abs(it.value());
    best = std::max(best, s);
  }
  return best;
}

double norm1(const Eigen::MatrixXd& A) { return A.size() ? A.cwiseAbs().colwise().sum().maxCoeff() : 0.0; }

}  // namespace igac
