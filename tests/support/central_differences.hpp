// SPDX-License-Identifier: BSD-3-Clause
// The Newton matrix of a NonlinearProblem against central differences of
// its residual, column by column, at a converged state: the one check of
// the large-deformation tangents (one body on an obstacle, two bodies).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "engine/load_stepping.hpp"

namespace igac_test {

// Compares J(t, x) with (R(x + h e_j) - R(x - h e_j)) / 2h for the columns
// `columns`, skipping a column whose step changes the active set (across
// the semismooth kink there is no derivative); returns how many were
// compared.  Central differences of a smooth residual: error ~ h^2 |R'''|
// plus round-off |R| eps / h; h = 1e-6 relative gives ~1e-8 of the column.
inline int expect_jacobian_matches_central_differences(igac::NonlinearProblem& problem, double t,
                                                        const Eigen::VectorXd& x, const std::vector<int>& columns,
                                                        double tolerance) {
  constexpr double kStep = 1e-6;
  Eigen::SparseMatrix<double> J;
  EXPECT_TRUE(problem.jacobian(t, x, J));
  const Eigen::MatrixXd Jd = Eigen::MatrixXd(J);
  const auto active = problem.active_set(t, x);
  int checked = 0;
  for (int j : columns) {
    const double h = kStep * std::max(1.0, std::abs(x[j]));
    Eigen::VectorXd xp = x, xm = x, rp, rm;
    xp[j] += h;
    xm[j] -= h;
    EXPECT_TRUE(problem.residual(t, xp, rp));
    const auto ap = problem.active_set(t, xp);
    EXPECT_TRUE(problem.residual(t, xm, rm));
    const auto am = problem.active_set(t, xm);
    if (ap != active || am != active) continue;
    const Eigen::VectorXd fd = (rp - rm) / (2 * h);
    const double scale = std::max(Jd.col(j).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((fd - Jd.col(j)).cwiseAbs().maxCoeff() / scale, tolerance) << "column " << j;
    ++checked;
  }
  return checked;
}

// The state the load-stepping driver reaches at t = 1 from x = 0 with the
// `primed` multipliers nearest the obstacle made active (activate_nearest),
// in `steps` steps of at most `max_increment`: where the tangent checks
// stand; *t gets the last step's load factor (1 to round-off).  The
// driver's status is checked.
template <class Problem>
Eigen::VectorXd converged_state(Problem& problem, double* t, int steps, double max_increment = 1.0, int primed = 1) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(problem.size());
  problem.activate_nearest(x, primed);
  igac::LoadSteppingOptions opt;
  opt.steps = steps;
  opt.quiet = true;
  opt.max_increment = max_increment;
  const igac::LoadSteppingSummary summary = igac::run_load_steps(problem, x, opt, {});
  EXPECT_EQ(summary.status, "converged");
  *t = summary.steps.empty() ? 0.0 : summary.steps.back().load_factor;
  return x;
}

}  // namespace igac_test
