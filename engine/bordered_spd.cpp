// SPDX-License-Identifier: BSD-3-Clause
#include "engine/bordered_spd.hpp"

namespace igac {

bool BorderedSpdSolver::compute(const Eigen::MatrixXd& S, const Eigen::MatrixXd& B) {
  n_ = int(S.rows());
  k_ = int(B.cols());
  if (n_ < k_) return false;
  if (k_ == 0) {
    T_.resize(0, 0);
    if (n_ == 0) return true;
    llt_.compute(S);
    return llt_.info() == Eigen::Success;
  }
  qr_.compute(B);
  R1_ = qr_.matrixQR().topRows(k_).triangularView<Eigen::Upper>();
  // rank: |R1_ii| against the largest column of B (relative round-off)
  constexpr double kRankTolerance = 1e-12;
  const double scale = B.colwise().norm().maxCoeff();
  for (int i = 0; i < k_; ++i)
    if (!(std::abs(R1_(i, i)) > kRankTolerance * scale)) return false;
  T_ = qr_.householderQ().adjoint() * S;
  T_ = T_ * qr_.householderQ();
  if (n_ == k_) return true;
  llt_.compute(T_.bottomRightCorner(n_ - k_, n_ - k_));
  return llt_.info() == Eigen::Success;
}

void BorderedSpdSolver::solve(const Eigen::VectorXd& r, const Eigen::VectorXd& q, Eigen::VectorXd& x,
                              Eigen::VectorXd& c) const {
  if (k_ == 0) {
    x = n_ > 0 ? Eigen::VectorXd(llt_.solve(r)) : Eigen::VectorXd();
    c.resize(0);
    return;
  }
  const Eigen::VectorXd w = R1_.transpose().triangularView<Eigen::Lower>().solve(q);
  const Eigen::VectorXd rho = qr_.householderQ().adjoint() * r;
  Eigen::VectorXd t(n_);
  t.head(k_) = w;
  if (n_ > k_) t.tail(n_ - k_) = llt_.solve(Eigen::VectorXd(rho.tail(n_ - k_) - T_.bottomLeftCorner(n_ - k_, k_) * w));
  c = R1_.triangularView<Eigen::Upper>().solve(Eigen::VectorXd(T_.topRows(k_) * t - rho.head(k_)));
  x = qr_.householderQ() * t;
}

}  // namespace igac
