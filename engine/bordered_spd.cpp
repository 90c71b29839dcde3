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

bool BorderedLuSolver::compute(const Eigen::MatrixXd& A, const Eigen::MatrixXd& Bc, const Eigen::MatrixXd& Bh) {
  n_ = int(A.rows());
  k_ = int(Bc.cols());
  if (n_ < k_ || Bh.cols() != k_) return false;
  if (k_ == 0) {
    if (n_ == 0) return true;
    lu_.compute(A);
    return !lu_.singular();
  }
  qr_rows_.compute(Bc);
  qr_unknowns_.compute(Bh);
  if (!full_column_rank(qr_rows_, Bc, R1c_) || !full_column_rank(qr_unknowns_, Bh, R1h_)) return false;
  T_ = qr_rows_.householderQ().adjoint() * A;
  T_ = T_ * qr_unknowns_.householderQ();
  if (n_ == k_) return true;
  lu_.compute(T_.bottomRightCorner(n_ - k_, n_ - k_));
  return !lu_.singular();
}

void BorderedLuSolver::solve(const Eigen::VectorXd& r, const Eigen::VectorXd& q, Eigen::VectorXd& x,
                             Eigen::VectorXd& c) const {
  if (k_ == 0) {
    x = n_ > 0 ? Eigen::VectorXd(lu_.solve(r)) : Eigen::VectorXd();
    c.resize(0);
    return;
  }
  const Eigen::VectorXd w = R1h_.transpose().triangularView<Eigen::Lower>().solve(q);
  const Eigen::VectorXd rho = qr_rows_.householderQ().adjoint() * r;
  Eigen::VectorXd t(n_);
  t.head(k_) = w;
  if (n_ > k_) t.tail(n_ - k_) = lu_.solve(Eigen::VectorXd(rho.tail(n_ - k_) - T_.bottomLeftCorner(n_ - k_, k_) * w));
  c = R1c_.triangularView<Eigen::Upper>().solve(Eigen::VectorXd(T_.topRows(k_) * t - rho.head(k_)));
  x = qr_unknowns_.householderQ() * t;
}

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
  if (!full_column_rank(qr_, B, R1_)) return false;
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
