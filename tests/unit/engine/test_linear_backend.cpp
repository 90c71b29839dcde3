// SPDX-License-Identifier: BSD-3-Clause
// The linear backend seam of the load-stepping driver (engine/linear_backend.hpp):
// an injected backend is the one every Newton step and tangent predictor
// solves with, and any backend that solves the block matrix gives the same
// run: a dense LU of assemble_full against the direct SaddleSolver, on a
// nonlinear problem with a constraint row that changes from inactive to
// active on the way (a semismooth Newton step) and an element-local unknown
// (the mixed formulation's condensation).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <tuple>

#include "engine/block_jacobian.hpp"
#include "engine/load_stepping.hpp"
#include "engine/saddle_solver.hpp"

using namespace igac;

namespace {

// Unknowns x = [u0, u1, l, z]: springs with a cubic hardening pulled by t,
// u0 held below g = 0.3 by a multiplier l (complementarity on g - u0 and
// -l, scale c), and z = u0 + u1 a local unknown tied to them.
//   R_u0 = u0 + 0.2 u0^3 + (u0 - u1) - t + l + 0.1 z
//   R_u1 = 2 u1 - (u0 - u1) - 0.5 t + 0.1 z
//   R_l  = active ? c (u0 - g) : l        (active: l + c (u0 - g) > 0)
//   R_z  = h (u0 + u1 - z)
class SpringsOnAStop final : public NonlinearProblem {
 public:
  static constexpr double g = 0.3, c = 1.0, h = 1.0;
  int size() const override { return 4; }
  static bool active(const Eigen::VectorXd& x) { return x[2] + c * (x[0] - g) > 0; }
  bool residual(double t, const Eigen::VectorXd& x, Eigen::VectorXd& r) override {
    r.resize(4);
    r[0] = x[0] + 0.2 * std::pow(x[0], 3) + (x[0] - x[1]) - t + x[2] + 0.1 * x[3];
    r[1] = 2 * x[1] - (x[0] - x[1]) - 0.5 * t + 0.1 * x[3];
    r[2] = active(x) ? c * (x[0] - g) : x[2];
    r[3] = h * (x[0] + x[1] - x[3]);
    return true;
  }
  bool jacobian(double, const Eigen::VectorXd&, Eigen::SparseMatrix<double>&) override { return false; }
  bool block_jacobian(double, const Eigen::VectorXd& x, BlockJacobian& J) override {
    // displacement block with the local unknown condensed: K_uu + C^T g C
    const double gz = 0.1;
    Eigen::MatrixXd K(2, 2);
    K << 2 + 0.6 * x[0] * x[0], -1, -1, 3;
    Eigen::SparseMatrix<double, Eigen::RowMajor> C(1, 2);
    C.insert(0, 0) = 1;
    C.insert(0, 1) = 1;
    const Eigen::MatrixXd CtgC = Eigen::MatrixXd(Eigen::SparseMatrix<double>(C.transpose()) * C) * gz;
    J.K = (K + CtgC).sparseView();
    J.B.resize(1, 2);
    J.B.insert(0, 0) = 1;
    J.s.resize(1);
    J.d.resize(1);
    J.s[0] = active(x) ? c : 0;
    J.d[0] = active(x) ? 0 : 1;
    J.local.C = C;
    J.local.g = Eigen::VectorXd::Constant(1, gz);
    J.local.h = Eigen::VectorXd::Constant(1, h);
    return true;
  }
  int active_set_size(double, const Eigen::VectorXd& x) const override { return active(x); }
  std::vector<char> active_set(double, const Eigen::VectorXd& x) const override { return {char(active(x))}; }
  double force_scale(double t, const Eigen::VectorXd&) override { return std::max(t, 1e-3); }
};

// The whole matrix (assemble_full) by dense LU, counting its calls.
class DenseLuBackend final : public LinearBackend {
 public:
  bool setup(const BlockJacobian& J) override {
    ++stats_.setups;
    lu_.compute(Eigen::MatrixXd(assemble_full(J)));
    return std::abs(lu_.determinant()) > 0;
  }
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double) override {
    ++stats_.solves;
    x = lu_.solve(b);
    return x.allFinite();
  }
  const std::string& why() const override { return why_; }
  const LinearSolveStats& stats() const override { return stats_; }
  double condition_estimate() const override { return 0; }
  LinearBackendReport report() const override { return {.type = "dense", .method = "partial-pivot LU"}; }

 private:
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  LinearSolveStats stats_;
  std::string why_;
};

LoadSteppingOptions options() {
  LoadSteppingOptions opt;
  opt.quiet = true;
  opt.steps = 4;
  opt.tolerance = 1e-12;
  return opt;
}

}  // namespace

TEST(LinearBackend, TheInjectedBackendSolvesEveryStepAndGivesTheDirectRun) {
  SpringsOnAStop problem;
  Eigen::VectorXd direct = Eigen::VectorXd::Zero(4), dense = direct;
  const LoadSteppingSummary a = run_load_steps(problem, direct, options(), {});
  DenseLuBackend backend;
  LoadSteppingOptions opt = options();
  opt.linear_backend = &backend;
  const LoadSteppingSummary b = run_load_steps(problem, dense, opt, {});
  ASSERT_EQ(a.status, "converged");
  ASSERT_EQ(b.status, "converged");
  // the stop is reached (u0 = g, l > 0 pushing back), the constraint active at the end
  EXPECT_NEAR(direct[0], SpringsOnAStop::g, 1e-12);
  EXPECT_GT(direct[2], 0);
  EXPECT_NEAR(direct[3], direct[0] + direct[1], 1e-12);
  EXPECT_EQ(a.steps.front().active_set_sizes.back(), 0);  // (open in the first step, closed in the last)
  EXPECT_EQ(a.steps.back().active_set_sizes.back(), 1);
  // every linear solve of the second run was the injected backend's ...
  EXPECT_GT(backend.stats().setups, 0);
  EXPECT_EQ(b.linear.setups, backend.stats().setups);
  EXPECT_EQ(b.linear.solves, backend.stats().solves);
  // ... and both backends, exact solves of the same matrices, take the same
  // steps to the same state (to round-off of a condition ~10 problem)
  ASSERT_EQ(a.steps.size(), b.steps.size());
  for (size_t i = 0; i < a.steps.size(); ++i) EXPECT_EQ(a.steps[i].newton_iterations, b.steps[i].newton_iterations);
  EXPECT_LE((direct - dense).cwiseAbs().maxCoeff(), 1e-13);
}

TEST(BlockJacobianRows, AnyRangeOfRowsIsThoseOfTheWholeCondensedMatrix) {
  // What a process hands to a distributed solver: its rows of the
  // condensed J (assemble_condensed) + extra, built without the whole; K_coupling
  // overlapping K's pattern (a follower load) and beside it (two bodies).
  const int n = 7, m = 3;
  BlockJacobian J;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), Kc = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = std::max(0, i - 2); j <= std::min(n - 1, i + 2); ++j) K(i, j) = 1.0 + 0.1 * i + 0.01 * j;
  Kc(1, 2) = 0.5;   // inside K's pattern
  Kc(0, 6) = -0.25;  // beside it
  J.K = K.sparseView();
  J.K.coeffRef(3, 3) = 0.0;  // an explicit zero of the pattern stays
  J.K_coupling = Kc.sparseView();
  J.B.resize(m, n);
  J.B.insert(0, 0) = 1.0;
  J.B.insert(0, 4) = 2.0;
  J.B.insert(1, 5) = -1.0;
  J.B.insert(2, 6) = 3.0;
  J.s = Eigen::Vector3d(10.0, 0.0, 5.0);
  J.d = Eigen::Vector3d(0.0, 2.0, 0.0);
  Eigen::SparseMatrix<double, Eigen::RowMajor> extra(n + m, n + m);
  extra.insert(4, 0) = 0.125;
  extra.insert(9, 9) = 4.0;
  // the condensed J written out densely, block by block
  Eigen::MatrixXd whole = Eigen::MatrixXd::Zero(n + m, n + m);
  const Eigen::MatrixXd B(J.B);
  whole.topLeftCorner(n, n) = Eigen::MatrixXd(J.K) + Kc;
  whole.topRightCorner(n, m) = B.transpose();
  whole.bottomLeftCorner(m, n) = J.s.asDiagonal() * B;
  whole.bottomRightCorner(m, m) = J.d.asDiagonal();
  whole += Eigen::MatrixXd(extra);
  EXPECT_EQ((Eigen::MatrixXd(assemble_condensed(J)) + Eigen::MatrixXd(extra) - whole).cwiseAbs().sum(), 0.0);
  for (const auto& [begin, end, columns] : {std::tuple{0, n + m, -1}, {0, 4, -1}, {4, 9, -1}, {6, n + m, -1},
                                            {2, n, n}, {0, 0, -1}}) {
    const Eigen::SparseMatrix<double, Eigen::RowMajor> R = condensed_rows(J, begin, end, columns, &extra);
    const int cols = columns < 0 ? n + m : columns;
    ASSERT_EQ(R.rows(), end - begin);
    ASSERT_EQ(R.cols(), cols);
    EXPECT_EQ((Eigen::MatrixXd(R) - whole.block(begin, 0, end - begin, cols)).cwiseAbs().sum(), 0.0)
        << begin << ", " << end;
    for (int r = 0; r < R.outerSize(); ++r) {
      int last = -1;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(R, r); it; ++it) {
        EXPECT_GT(it.col(), last);  // increasing, each column once
        last = int(it.col());
      }
    }
    if (begin <= 3 && 3 < end) EXPECT_EQ(R.innerVector(3 - begin).nonZeros(), 5);  // K(3, 3) = 0 kept
  }
}
