// SPDX-License-Identifier: BSD-3-Clause
// The Schur complement of the active constraint rows, G_A K^-1 G_A^T, on the
// factor of K, shared by the frictionless solve (contact/small_strain_contact)
// and the frictional one (contact/small_strain_friction), whose rows are the
// normal and the tangential ones stacked.  See small_strain_contact.hpp.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <vector>

#include "contact/small_strain_contact.hpp"
#include "engine/cholesky.hpp"
#include "engine/dense_kernels.hpp"

namespace igac {
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// What the active-set iterations need of K^-1: S_AA, G K^-1 f, and
// G K^-1 G_A^T lambda_A for every multiplier.  Columns Y_K = L^-1 P G_K^T of
// the multipliers that become active are computed on the reach of the
// contact zone, each once; gaps come from a backward solve on the reach of
// the face (with the face ordered last, both are the trailing block).
class ActiveSchur {
 public:
  ActiveSchur(const SparseCholesky& chol, const RowSparse& Gp, const Eigen::VectorXd& fp, ContactSolution& sol)
      : chol_(chol), Gp_(Gp), sol_(sol), slot_(Gp.rows(), -1) {
    face_ = chol.reach(equations_of(all_multipliers()));
    sol.reach_rows = int(face_.rows.size());
    face_local_.assign(chol.size(), -1);
    for (size_t i = 0; i < face_.rows.size(); ++i) face_local_[face_.rows[i]] = int(i);
    const Eigen::VectorXd yf = chol.forward_full(fp);
    yf_face_.resize(Eigen::Index(face_.rows.size()));
    for (size_t i = 0; i < face_.rows.size(); ++i) yf_face_[i] = yf[face_.rows[i]];
  }
  Eigen::VectorXd G_solve_f() const { return G_times_backward(yf_face_); }
  // Makes the columns of A available; returns S_AA.
  Eigen::MatrixXd S_active(const std::vector<int>& A) {
    prepare(A);
    std::vector<int> s(A.size());
    for (size_t i = 0; i < A.size(); ++i) s[i] = slot_[A[i]];
    return S_(s, s);
  }
  // Makes the columns of A available without copying S_AA out: then
  // S(K1, K2) reads its entries (K1, K2 in A).
  void prepare(const std::vector<int>& A) {
    std::vector<int> fresh;
    for (int K : A)
      if (slot_[K] < 0) fresh.push_back(K);
    if (!fresh.empty()) add_columns(fresh);
  }
  double S(int K1, int K2) const { return S_(slot_[K1], slot_[K2]); }
  // The multipliers whose columns were computed, batch by batch in the
  // order they were: S_active of each again, in a fresh ActiveSchur of the
  // same factor, gives the same columns and S, bit for bit.
  const std::vector<std::vector<int>>& batches() const { return batches_; }
  // G K^-1 G_A^T lambda_A for all multipliers (lambda zero outside A).
  Eigen::VectorXd G_solve_Gt(const std::vector<int>& A, const Eigen::VectorXd& lambda) const {
    Eigen::VectorXd y = Eigen::VectorXd::Zero(yf_face_.size());
    Eigen::VectorXd ly = Eigen::VectorXd::Zero(Y_.cols());
    for (int K : A) ly[slot_[K]] = lambda[K];
    const Eigen::VectorXd yl = Y_ * ly;
    for (size_t i = 0; i < zone_.rows.size(); ++i) y[face_local_[zone_.rows[i]]] = yl[i];
    return G_times_backward(y);
  }

 private:
  std::vector<int> all_multipliers() const {
    std::vector<int> all(Gp_.rows());
    for (int K = 0; K < int(all.size()); ++K) all[K] = K;
    return all;
  }
  std::vector<int> equations_of(const std::vector<int>& multipliers) const {
    std::vector<int> eqs;
    for (int K : multipliers)
      for (RowSparse::InnerIterator it(Gp_, K); it; ++it) eqs.push_back(it.col());
    return eqs;
  }
  // G P^T x for x = L^-T y on the face's reach (G reads x there only).
  Eigen::VectorXd G_times_backward(const Eigen::VectorXd& y) const {
    const Eigen::VectorXd x = chol_.backward(face_, y);
    Eigen::VectorXd out = Eigen::VectorXd::Zero(Gp_.rows());
    for (int K = 0; K < Gp_.rows(); ++K)
      for (RowSparse::InnerIterator it(Gp_, K); it; ++it)
        out[K] += it.value() * x[face_local_[chol_.position(it.col())]];
    return out;
  }
  // One blocked forward pass for the new columns on the grown zone reach.
  void add_columns(const std::vector<int>& fresh) {
    std::vector<int> all = ever_;
    all.insert(all.end(), fresh.begin(), fresh.end());
    SparseCholesky::Reach zone = chol_.reach(equations_of(all));
    // the old columns, laid out on the new rows (zero on the rows added)
    Eigen::MatrixXd Y;
    if (!ever_.empty()) {
      Y = Eigen::MatrixXd::Zero(Eigen::Index(zone.rows.size()), Eigen::Index(all.size()));
      std::vector<int> at(chol_.size(), -1);
      for (size_t i = 0; i < zone.rows.size(); ++i) at[zone.rows[i]] = int(i);
      for (size_t i = 0; i < zone_.rows.size(); ++i) Y.row(at[zone_.rows[i]]).head(Y_.cols()) = Y_.row(i);
    }
    Eigen::SparseMatrix<double> C(Gp_.cols(), Eigen::Index(fresh.size()));
    {
      std::vector<Eigen::Triplet<double>> t;
      for (size_t j = 0; j < fresh.size(); ++j)
        for (RowSparse::InnerIterator it(Gp_, fresh[j]); it; ++it) t.emplace_back(it.col(), int(j), it.value());
      C.setFromTriplets(t.begin(), t.end());
    }
    // the new columns in the order of their first row (forward_by_start)
    SparseCholesky::ColumnsByStart added = chol_.forward_by_start(zone, C);
    if (ever_.empty())
      Y = std::move(added.Y);
    else
      Y.rightCols(Eigen::Index(fresh.size())) = added.Y;
    for (size_t j = 0; j < fresh.size(); ++j) all[ever_.size() + j] = fresh[added.order[j]];
    const Eigen::Index old = Y_.cols(), total = Eigen::Index(all.size());
    Eigen::MatrixXd S(total, total);
    S.topLeftCorner(old, old) = S_;
    if (old == 0) {
      S = dense::gram(Y, added.start);
    } else {
      dense::gemm(1.0, Y, true, Y.rightCols(total - old), false, 0.0, S.rightCols(total - old));
      S.bottomLeftCorner(total - old, old) = S.topRightCorner(old, total - old).transpose();
    }
    for (Eigen::Index j = old; j < total; ++j) slot_[all[j]] = int(j);
    S_ = std::move(S);
    Y_ = std::move(Y);
    zone_ = std::move(zone);
    ever_ = std::move(all);
    batches_.push_back(fresh);
    sol_.schur_columns += int(fresh.size());
  }

  const SparseCholesky& chol_;
  const RowSparse& Gp_;
  ContactSolution& sol_;
  SparseCholesky::Reach face_;    // reach of every contact-face equation
  std::vector<int> face_local_;   // factor position -> row in face_ (-1: outside)
  Eigen::VectorXd yf_face_;       // L^-1 P f_p on face_
  SparseCholesky::Reach zone_;    // reach of the multipliers with a column
  std::vector<int> ever_;         // those multipliers, in column order
  std::vector<std::vector<int>> batches_;  // ever_ as add_columns took them
  std::vector<int> slot_;         // multiplier -> column (-1: none yet)
  Eigen::MatrixXd Y_;             // zone_.rows x ever_
  Eigen::MatrixXd S_;             // ever_ x ever_
};

}  // namespace igac
