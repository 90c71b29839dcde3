// SPDX-License-Identifier: BSD-3-Clause
// The small dense system both contact solvers end with: the Schur complement
// S of the active multipliers bordered by the rigid motions they must hold,
//     [ S     -B ] [x]   [ r ]        S: n x n, SPD on the null space of B^T
//     [ -B^T   0 ] [c] = [ -q ]       B: n x k, full column rank (k <= 6)
// (S = G_A K^-1 G_A^T, B = G_A R, q = R^T f: the multipliers balance the
// load along every rigid motion).  Null-space method (Nocedal & Wright,
// Numerical Optimization, sec. 16.2): B = Q [R1; 0], x = Q [w; mu] with
// R1^T w = q, then (Q^T S Q)_22 mu = (Q^T r)_2 - (Q^T S Q)_21 w by Cholesky,
// and c from the first k rows.  The balance B^T x = q holds to round-off
// whatever the size of c (eliminating c through S^-1 B instead loses it to
// cancellation when the load is tiny against the initial gaps), and the
// Cholesky factor is blocked, unlike a full-pivoting LU of the whole system.
#pragma once

#include <Eigen/Dense>

#include "engine/dense_kernels.hpp"

namespace igac {

// The reduced matrix's factorisation, by Cholesky (SPD) or by LU.
struct CholeskyFactor {
  Eigen::LLT<Eigen::MatrixXd> llt;
  void compute(const Eigen::Ref<const Eigen::MatrixXd>& A) { llt.compute(A); }
  bool singular() const { return llt.info() != Eigen::Success; }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const { return llt.solve(b); }
};

// The null-space method on [A -Bc; -Bh^T 0] (below), the reduced matrix
// (Qc^T A Qh)_22 factorised by `Factor`.
template <class Factor>
class NullSpaceBordered {
 public:
  // False when Bc or Bh does not have full column rank, or the reduced
  // matrix is singular (not positive definite for the Cholesky factor).
  bool compute(const Eigen::MatrixXd& A, const Eigen::MatrixXd& Bc, const Eigen::MatrixXd& Bh);
  void solve(const Eigen::VectorXd& r, const Eigen::VectorXd& q, Eigen::VectorXd& x, Eigen::VectorXd& c) const;

 private:
  int n_ = 0, k_ = 0;
  Eigen::HouseholderQR<Eigen::MatrixXd> qr_rows_, qr_unknowns_;  // of Bc, of Bh
  Eigen::MatrixXd R1c_, R1h_, T_;  // T = Qc^T A Qh
  Factor factor_;
};

class BorderedSpdSolver {
 public:
  // False when B does not have full column rank (the multipliers cannot
  // hold the rigid motions) or S is not positive definite on its null space.
  bool compute(const Eigen::MatrixXd& S, const Eigen::MatrixXd& B) { return impl_.compute(S, B, B); }
  void solve(const Eigen::VectorXd& r, const Eigen::VectorXd& q, Eigen::VectorXd& x, Eigen::VectorXd& c) const {
    impl_.solve(r, q, x, c);
  }

 private:
  NullSpaceBordered<CholeskyFactor> impl_;
};

// The same border on a general square A whose two borders differ (friction:
// a sliding multiplier's force direction is not its constraint row),
//     [ A      -Bc ] [x]   [ r ]      A: n x n, Bc, Bh: n x k, full column rank
//     [ -Bh^T   0  ] [c] = [ -q ]
// by the same null-space method with Bh = Qh [R1h; 0] on the unknowns and
// Bc = Qc [R1c; 0] on the rows: x = Qh [w; mu], R1h^T w = q, then
// (Qc^T A Qh)_22 mu = (Qc^T r)_2 - (Qc^T A Qh)_21 w by a partial-pivoting
// LU (engine/dense_kernels, blocked; singular when a pivot falls below
// n eps of the largest, as a full-pivoting LU's rank), and c from the first
// k rows.
using BorderedLuSolver = NullSpaceBordered<dense::Lu>;

}  // namespace igac
