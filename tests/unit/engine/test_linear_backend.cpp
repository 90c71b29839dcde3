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

namespace {

// A block matrix with m constraint rows on an SPD K (a chain of springs,
// held at its first node): the Schur complement is what depends on the set.
BlockJacobian chain_with_stops(int n, int m) {
  BlockJacobian J;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, i == 0 ? 3.0 : 2.0 + 0.01 * i);
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0), t.emplace_back(i + 1, i, -1.0);
  }
  J.K.resize(n, n);
  J.K.setFromTriplets(t.begin(), t.end());
  J.B.resize(m, n);
  for (int k = 0; k < m; ++k) {  // row k: a weighted gap of two neighbouring nodes
    const int i = (k * (n - 1)) / m;
    J.B.insert(k, i) = 0.75;
    J.B.insert(k, i + 1) = 0.25;
  }
  J.s = Eigen::VectorXd::Zero(m);
  J.d = Eigen::VectorXd::Zero(m);
  for (int k = 0; k < m; ++k) {
    if (k % 3 == 0) J.s[k] = 2.0;  // active: s B du = b
    else J.d[k] = 0.5;             // inactive: d dl = b
  }
  return J;
}

}  // namespace

// SaddleSolver::update_constraint_rows (new active rows, same K: the Schur
// complement alone is formed again) solves as a solver set up afresh on the
// changed matrix, and as a dense LU of it.
TEST(SaddleSolver, NewActiveRowsSolveAsAFreshSetup) {
  const int n = 40, m = 9;
  BlockJacobian J = chain_with_stops(n, m);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n + m, -1.0, 2.0);
  SaddleSolver kept;
  ASSERT_TRUE(kept.setup(J));
  Eigen::VectorXd x;
  ASSERT_TRUE(kept.solve(b, x));
  for (int k = 0; k < m; ++k) {  // every row's decision turned over
    const bool was_active = J.s[k] != 0;
    J.s[k] = was_active ? 0.0 : 2.0;
    J.d[k] = was_active ? 0.5 : 0.0;
  }
  ASSERT_TRUE(kept.update_constraint_rows(J));
  Eigen::VectorXd updated, fresh_x;
  ASSERT_TRUE(kept.solve(b, updated));
  SaddleSolver fresh;
  ASSERT_TRUE(fresh.setup(J));
  ASSERT_TRUE(fresh.solve(b, fresh_x));
  const Eigen::VectorXd dense = Eigen::MatrixXd(assemble_full(J)).partialPivLu().solve(b);
  EXPECT_GT((updated - x).norm(), 1e-3 * x.norm());  // the rows did change the solution
  EXPECT_LE((updated - fresh_x).norm(), 1e-12 * fresh_x.norm());
  EXPECT_LE((updated - dense).norm(), 1e-12 * dense.norm());
  EXPECT_EQ(kept.stats().setups, 1);  // (no second factorisation)
}

namespace {

// Nodes on springs pulled down onto stops, linear: the contact problem in
// its simplest form.  u_i: node i, a chain with a spring to ground at each
// node, the load t f_i pushing every node down onto its stop at -g_i; l_i
// the stop's multiplier.  Started with every stop closed, the semismooth
// Newton step opens the stops whose multiplier pulls a few at a time; with
// the inner active-set loop the linearised problem (here the problem
// itself) is solved in one Newton iteration.
class ChainOnStops final : public NonlinearProblem {
 public:
  static constexpr int n = 30;
  static constexpr double c = 1.0;
  Eigen::VectorXd gap, force;
  Eigen::MatrixXd K;
  bool inner_loop = true;
  ChainOnStops() : gap(n), force(n), K(Eigen::MatrixXd::Zero(n, n)) {
    for (int i = 0; i < n; ++i) {
      const double s = double(i) / (n - 1);
      gap[i] = 0.02 + 0.5 * (s - 0.5) * (s - 0.5);  // a parabolic obstacle: the middle touches first
      force[i] = -1.0 / n;
      K(i, i) = 0.05 + 2.0;
      if (i + 1 < n) K(i, i + 1) = K(i + 1, i) = -1.0;
    }
  }
  int size() const override { return 2 * n; }
  // stop i closed: l_i + c (-u_i - gap_i) > 0, l_i >= 0 pushes up
  static std::vector<char> decide(const Eigen::VectorXd& gamma, const Eigen::VectorXd& l) {
    std::vector<char> a(n);
    for (int i = 0; i < n; ++i) a[i] = l[i] + c * gamma[i] > 0;
    return a;
  }
  Eigen::VectorXd gamma_of(const Eigen::VectorXd& x) const { return -x.head(n) - gap; }
  bool residual(double t, const Eigen::VectorXd& x, Eigen::VectorXd& r) override {
    r.resize(2 * n);
    const Eigen::VectorXd u = x.head(n), l = x.tail(n), gamma = gamma_of(x);
    r.head(n) = K * u - t * force - l;  // B = d gamma / du = -I: B^T l = -l
    const auto a = decide(gamma, l);
    for (int i = 0; i < n; ++i) r[n + i] = a[i] ? c * gamma[i] : l[i];
    return true;
  }
  bool jacobian(double, const Eigen::VectorXd&, Eigen::SparseMatrix<double>&) override { return false; }
  bool block_jacobian(double, const Eigen::VectorXd& x, BlockJacobian& J) override {
    J.K = K.sparseView();
    J.B.resize(n, n);
    for (int i = 0; i < n; ++i) J.B.insert(i, i) = -1.0;
    const auto a = decide(gamma_of(x), x.tail(n));
    J.s = Eigen::VectorXd::Zero(n);
    J.d = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) {
      J.s[i] = a[i] ? c : 0.0;
      J.d[i] = a[i] ? 0.0 : 1.0;
    }
    at_jacobian = x;
    return true;
  }
  bool relinearise_active_set(const Eigen::VectorXd& dx, BlockJacobian& J, Eigen::VectorXd& rhs) override {
    if (!inner_loop) return false;
    const Eigen::VectorXd moved = at_jacobian + dx;
    const auto a = decide(gamma_of(moved), moved.tail(n));
    const Eigen::VectorXd gamma = gamma_of(at_jacobian);
    bool changed = false;
    for (int i = 0; i < n; ++i) {
      if (bool(a[i]) == (J.s[i] != 0)) continue;
      changed = true;
      J.s[i] = a[i] ? c : 0.0, J.d[i] = a[i] ? 0.0 : 1.0;
      rhs[n + i] = -(a[i] ? c * gamma[i] : at_jacobian[n + i]);
    }
    return changed;
  }
  int active_set_size(double, const Eigen::VectorXd& x) const override {
    const auto a = decide(gamma_of(x), x.tail(n));
    return int(std::count(a.begin(), a.end(), 1));
  }
  double force_scale(double t, const Eigen::VectorXd&) override { return std::max(t, 1e-3); }

 private:
  Eigen::VectorXd at_jacobian;
};

}  // namespace

// The Newton driver's inner active-set loop (NonlinearProblem::
// relinearise_active_set): started from every stop closed, the linear
// contact problem is solved in one Newton iteration, where the semismooth
// step alone takes several (a few stops opened per iteration), and both
// reach the same state.
TEST(NewtonActiveSet, TheLinearisedContactProblemIsSolvedInOneNewtonIteration) {
  LoadSteppingOptions opt = options();
  opt.steps = 1;
  opt.tangent_predictor = false;
  opt.line_search = false;
  ChainOnStops with, without;
  without.inner_loop = false;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * ChainOnStops::n), y = x;
  x.tail(ChainOnStops::n).setConstant(1.0), y = x;  // every stop closed at the start
  const LoadSteppingSummary a = run_load_steps(with, x, opt, {});
  const LoadSteppingSummary b = run_load_steps(without, y, opt, {});
  ASSERT_EQ(a.status, "converged");
  ASSERT_EQ(b.status, "converged");
  EXPECT_EQ(a.steps.front().newton_iterations, 1);
  EXPECT_GE(b.steps.front().newton_iterations, 3);
  const int final_set = a.steps.front().active_set_sizes.back();
  EXPECT_GT(final_set, 0);
  EXPECT_LT(final_set, ChainOnStops::n);
  EXPECT_EQ(b.steps.front().active_set_sizes.back(), final_set);
  EXPECT_LE((x - y).cwiseAbs().maxCoeff(), 1e-12);
}
