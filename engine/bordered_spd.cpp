// SPDX-License-Identifier: BSD-3-Clause
#include "engine/bordered_spd.hpp"

#include <cmath>

namespace igac {

namespace {
// The triangular factor R1 of B = Q [R1; 0], false when B is rank deficient:
// |R1_ii| against the largest column of B (relative round-off).
bool full_column_rank(const Eigen::HouseholderQR<Eigen::MatrixXd>& qr, const Eigen::MatrixXd& B, Eigen::MatrixXd& R1) {
  const int k = int(B.cols());
  R1 = qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
  constexpr double kRankTolerance = 1e-12;
  const double scale = B.colwise().norm().maxCoeff();
  for (int i = 0; i < k; ++i)
    if (!(std::abs(R1(i, i)) > kRankTolerance * scale)) return false;
  return true;
}

}  // namespace

template <class Factor>
bool NullSpaceBordered<Factor>::compute(const Eigen::MatrixXd& A, const Eigen::MatrixXd& Bc, const Eigen::MatrixXd& Bh) {
  n_ = int(A.rows());
  k_ = int(Bc.cols());
  if (n_ < k_ || Bh.cols() != k_) return false;
  if (k_ == 0) {
    T_.resize(0, 0);
    if (n_ == 0) return true;
    factor_.compute(A);
    return !factor_.singular();
  }
  qr_rows_.compute(Bc);
  qr_unknowns_.compute(Bh);
  if (!full_column_rank(qr_rows_, Bc, R1c_) || !full_column_rank(qr_unknowns_, Bh, R1h_)) return false;
  T_ = A;  // Qc^T A Qh in place: no temporary of A's size
  qr_rows_.householderQ().adjoint().applyThisOnTheLeft(T_);
  qr_unknowns_.householderQ().applyThisOnTheRight(T_);
  if (n_ == k_) return true;
  factor_.compute(T_.bottomRightCorner(n_ - k_, n_ - k_));
  return !factor_.singular();
}

template <class Factor>
void NullSpaceBordered<Factor>::solve(const Eigen::VectorXd& r, const Eigen::VectorXd& q, Eigen::VectorXd& x,
                                      Eigen::VectorXd& c) const {
  if (k_ == 0) {
    x = n_ > 0 ? Eigen::VectorXd(factor_.solve(r)) : Eigen::VectorXd();
    c.resize(0);
    return;
  }
  const Eigen::VectorXd w = R1h_.transpose().triangularView<Eigen::Lower>().solve(q);
  const Eigen::VectorXd rho = qr_rows_.householderQ().adjoint() * r;
  Eigen::VectorXd t(n_);
  t.head(k_) = w;
  if (n_ > k_) t.tail(n_ - k_) = factor_.solve(Eigen::VectorXd(rho.tail(n_ - k_) - T_.bottomLeftCorner(n_ - k_, k_) * w));
  c = R1c_.triangularView<Eigen::Upper>().solve(Eigen::VectorXd(T_.topRows(k_) * t - rho.head(k_)));
  x = qr_unknowns_.householderQ() * t;
}

template class NullSpaceBordered<CholeskyFactor>;
template class NullSpaceBordered<dense::Lu>;

}  // namespace igac
