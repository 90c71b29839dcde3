// SPDX-License-Identifier: BSD-3-Clause
#include "contact/finite_strain_mortar.hpp"

#include <exception>
#include <stdexcept>

#include "engine/free_cores.hpp"
#include "engine/numerical_failure.hpp"
#include "engine/sparsity.hpp"

namespace igac {

const std::vector<MortarPointCache::Point>& MortarPointCache::at(const ContactFace& slave, const MasterSurface& master,
                                                                 MortarIntegration integration, const Eigen::MatrixXd& u,
                                                                 const ContactQuadrature& tabulated) {
  if (valid_ && u_.rows() == u.rows() && u_.cols() == u.cols() && u_ == u) return points_;
  valid_ = false;  // until filled: a search that throws leaves no stale points behind
  points_.clear();
  if (master.num_elements() == 0) throw std::invalid_argument("a contact's master surface has no elements");
  for_each_mortar_point(slave, master, integration, &u, [&](const MortarSlavePoint& sp) {
    points_.push_back({sp, MasterPoint{}});
  }, &tabulated);
  // The closest-point searches, independent of one another: on the free
  // cores (each point's projection is the same on any thread).  What one
  // throws is rethrown here (none may leave an OpenMP region).
  const int n = int(points_.size());
  std::exception_ptr failure;
  bool lost = false;  // a point with no nearest element (not finite: MasterSurface::update refuses that first)
#pragma omp parallel for schedule(dynamic, 64) num_threads(free_cores()) if (n >= 256)
  for (int i = 0; i < n; ++i) {
    try {
      std::optional<MasterPoint> mp = master.project(points_[size_t(i)].slave.x);
      if (mp) points_[size_t(i)].master = std::move(*mp);
      else {
#pragma omp atomic write
        lost = true;
      }
    } catch (...) {
#pragma omp critical(igac_mortar_point_cache)
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
  if (lost) throw NumericalFailure("a slave point of a contact has a position that is not finite");
  u_ = u;
  valid_ = true;
  return points_;
}

namespace {

// Sums the dense blocks of consecutive mortar points that share their rows
// (the points of one slave element: its multipliers, or its equations) and
// hands them on as one triplet per entry, not one per entry and point: a
// 3D two-body Jacobian had about a million triplets of G for 196 rows.  An
// entry exists where some point added to it, zero or not, as before.
class BlockSum {
 public:
  explicit BlockSum(int num_columns) : slot_(size_t(num_columns), -1) {}
  // Makes `rows` the block's rows, flushing the last block into `out`
  // when they differ.  `transposed`: out gets (column, row, value).
  void rows(const std::vector<int>& rows, std::vector<Eigen::Triplet<double>>& out, bool transposed = false) {
    if (rows == rows_) return;
    flush(out, transposed);
    rows_ = rows;
  }
  // += v at (rows()[r], column).
  void add(int r, int column, double v) {
    int& c = slot_[size_t(column)];
    if (c < 0) {
      c = int(columns_.size());
      columns_.push_back(column);
      values_.resize(values_.size() + rows_.size(), 0.0);
      touched_.resize(touched_.size() + rows_.size(), 0);
    }
    const size_t at = size_t(c) * rows_.size() + size_t(r);
    values_[at] += v;
    touched_[at] = 1;
  }
  void flush(std::vector<Eigen::Triplet<double>>& out, bool transposed = false) {
    for (size_t c = 0; c < columns_.size(); ++c) {
      for (size_t r = 0; r < rows_.size(); ++r) {
        const size_t at = c * rows_.size() + r;
        if (!touched_[at]) continue;
        if (transposed) out.emplace_back(columns_[c], rows_[r], values_[at]);
        else out.emplace_back(rows_[r], columns_[c], values_[at]);
      }
      slot_[size_t(columns_[c])] = -1;
    }
    columns_.clear();
    values_.clear();
    touched_.clear();
  }

 private:
  std::vector<int> slot_;  // per column: its place in columns_, or -1
  std::vector<int> rows_, columns_;
  std::vector<double> values_;  // column by column
  std::vector<char> touched_;
};

}  // namespace

void add_finite_strain_mortar(const DofMap& dofs, const ContactFace& slave, MasterSurface& master,
                              MortarIntegration integration, const Eigen::MatrixXd& u, const Eigen::VectorXd& lambda,
                              int offset, const FiniteStrainMortarTerms& out, const ContactQuadrature& tabulated,
                              MortarPointCache& points) {
  master.update(u);
  const int dim = dofs.dim(), pd = dim - 1;
  std::vector<int> master_local, master_cps, eq_s, eq_m, eq_block, rows;
  Eigen::VectorXd R;
  Eigen::MatrixXd dR, P, W, H, block;
  const int num_free = dofs.num_free();
  BlockSum G(out.G ? num_free : 0), slave_master(out.K_coupling ? num_free : 0),
      master_slave(out.K_coupling ? num_free : 0);
  for (const MortarPointCache::Point& point : points.at(slave, master, integration, u, tabulated)) {
    const MortarSlavePoint& sp = point.slave;
    const MasterPoint* mp = &point.master;
    double lambda_B = 0;  // sum_K lambda_K B_K at the point, times the weight
    for (size_t k = 0; k < sp.K.size(); ++k) {
      const double bw = sp.B[k] * sp.JxW;
      (*out.gamma)[offset + sp.K[k]] += mp->gap * bw;
      lambda_B += lambda[sp.K[k]] * bw;
    }
    if (out.resultant) *out.resultant -= lambda_B * mp->normal;
    if (!out.G && (!out.force || lambda_B == 0.0)) continue;
    const NurbsPatch& face = master.side_patch(mp->side);
    face.rational_basis(mp->xi, master_local, R, dR);
    const std::vector<int>& side_cps = master.side_control_points(mp->side);
    master_cps.resize(master_local.size());
    for (size_t b = 0; b < master_local.size(); ++b) master_cps[b] = side_cps[master_local[b]];
    dofs.element_equations(sp.cps, eq_s);
    dofs.element_equations(master_cps, eq_m);
    const Eigen::VectorXd& n = mp->normal;
    const int ns = int(sp.cps.size()), nm = int(master_cps.size());
    if (out.force) {  // sum_K lambda_K d gamma_K / d u at this point: lambda_B (N_a n on the slave, -R_b n on the master)
      for (int a = 0; a < ns; ++a)
        for (int i = 0; i < dim; ++i)
          if (eq_s[a * dim + i] >= 0) (*out.force)[eq_s[a * dim + i]] += lambda_B * sp.N[a] * n[i];
      for (int b = 0; b < nm; ++b)
        for (int i = 0; i < dim; ++i)
          if (eq_m[b * dim + i] >= 0) (*out.force)[eq_m[b * dim + i]] -= lambda_B * R[b] * n[i];
    }
    if (!out.G) continue;
    // delta g = (delta x_s - delta x_m) . n
    rows.resize(sp.K.size());
    for (size_t k = 0; k < sp.K.size(); ++k) rows[k] = offset + sp.K[k];
    G.rows(rows, *out.G);
    for (size_t k = 0; k < sp.K.size(); ++k) {
      const double bw = sp.B[k] * sp.JxW;
      if (bw == 0.0) continue;
      for (int a = 0; a < ns; ++a)
        for (int i = 0; i < dim; ++i)
          if (eq_s[a * dim + i] >= 0) G.add(int(k), eq_s[a * dim + i], bw * sp.N[a] * n[i]);
      for (int b = 0; b < nm; ++b)
        for (int i = 0; i < dim; ++i)
          if (eq_m[b * dim + i] >= 0) G.add(int(k), eq_m[b * dim + i], -bw * R[b] * n[i]);
    }
    if (!out.K || lambda_B == 0.0) continue;
    // lambda_B Delta delta g over the local dofs: the slave's, then the master's
    const Eigen::MatrixXd a = face.jacobian(mp->xi);  // current tangents, dim x pd
    const Eigen::MatrixXd second = face.second_derivatives(mp->xi);
    const Eigen::MatrixXd m = a.transpose() * a;
    Eigen::MatrixXd b(pd, pd);
    for (int al = 0; al < pd; ++al)
      for (int be = 0; be < pd; ++be) b(al, be) = n.dot(second.col(al * pd + be));
    const double g = mp->gap;
    const Eigen::MatrixXd A_inv = (m - g * b).inverse();
    const Eigen::MatrixXd C = m.inverse() * b * A_inv;
    const int nd = (ns + nm) * dim;
    P.setZero(pd, nd);  // a_a . D
    W.setZero(pd, nd);  // n . delta a_a
    for (int s = 0; s < ns; ++s)
      for (int i = 0; i < dim; ++i) P.col(s * dim + i) = sp.N[s] * a.row(i).transpose();
    for (int r = 0; r < nm; ++r)
      for (int i = 0; i < dim; ++i) {
        P.col((ns + r) * dim + i) = -R[r] * a.row(i).transpose();
        W.col((ns + r) * dim + i) = n[i] * dR.row(r).transpose();
      }
    const Eigen::MatrixXd AP = A_inv * P;
    H.noalias() = -W.transpose() * AP;
    H += H.transpose().eval();  // -(W^T A^-1 P + P^T A^-1 W)
    H.noalias() -= g * W.transpose() * (A_inv * W);
    H.noalias() -= P.transpose() * (C * P);
    H *= lambda_B;
    // in the pattern: each side's own block; the slave-master blocks beside it
    block = H.topLeftCorner(ns * dim, ns * dim);
    scatter_element_matrix(*out.K, out.K->valuePtr(), eq_s, block);
    block = H.bottomRightCorner(nm * dim, nm * dim);
    scatter_element_matrix(*out.K, out.K->valuePtr(), eq_m, block);
    if (!out.K_coupling) continue;
    slave_master.rows(eq_s, *out.K_coupling);
    master_slave.rows(eq_s, *out.K_coupling, true);  // (kept as its transpose: the same rows)
    for (int r = 0; r < ns * dim; ++r) {
      if (eq_s[r] < 0) continue;
      for (int c = 0; c < nm * dim; ++c) {
        if (eq_m[c] < 0) continue;
        slave_master.add(r, eq_m[c], H(r, ns * dim + c));
        master_slave.add(r, eq_m[c], H(ns * dim + c, r));
      }
    }
  }
  if (out.G) G.flush(*out.G);
  if (out.K_coupling) {
    slave_master.flush(*out.K_coupling);
    master_slave.flush(*out.K_coupling, true);
  }
}

}  // namespace igac
