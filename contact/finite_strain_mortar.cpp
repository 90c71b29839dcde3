// SPDX-License-Identifier: BSD-3-Clause
#include "contact/finite_strain_mortar.hpp"

#include <stdexcept>

#include "engine/free_cores.hpp"
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
  // cores (each point's projection is the same on any thread).
  const int n = int(points_.size());
#pragma omp parallel for schedule(dynamic, 64) num_threads(free_cores()) if (n >= 256)
  for (int i = 0; i < n; ++i) points_[size_t(i)].master = *master.project(points_[size_t(i)].slave.x);
  u_ = u;
  valid_ = true;
  return points_;
}

void add_finite_strain_mortar(const DofMap& dofs, const ContactFace& slave, MasterSurface& master,
                              MortarIntegration integration, const Eigen::MatrixXd& u, const Eigen::VectorXd& lambda,
                              int offset, const FiniteStrainMortarTerms& out, const ContactQuadrature& tabulated,
                              MortarPointCache& points) {
  master.update(u);
  const int dim = dofs.dim(), pd = dim - 1;
  std::vector<int> master_local, master_cps, eq_s, eq_m, eq_block;
  Eigen::VectorXd R;
  Eigen::MatrixXd dR, P, W, H, block;
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
    for (size_t k = 0; k < sp.K.size(); ++k) {
      const double bw = sp.B[k] * sp.JxW;
      if (bw == 0.0) continue;
      const int row = offset + sp.K[k];
      for (int a = 0; a < ns; ++a)
        for (int i = 0; i < dim; ++i)
          if (eq_s[a * dim + i] >= 0) out.G->emplace_back(row, eq_s[a * dim + i], bw * sp.N[a] * n[i]);
      for (int b = 0; b < nm; ++b)
        for (int i = 0; i < dim; ++i)
          if (eq_m[b * dim + i] >= 0) out.G->emplace_back(row, eq_m[b * dim + i], -bw * R[b] * n[i]);
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
    for (int r = 0; r < ns * dim; ++r) {
      if (eq_s[r] < 0) continue;
      for (int c = 0; c < nm * dim; ++c) {
        if (eq_m[c] < 0) continue;
        out.K_coupling->emplace_back(eq_s[r], eq_m[c], H(r, ns * dim + c));
        out.K_coupling->emplace_back(eq_m[c], eq_s[r], H(ns * dim + c, r));
      }
    }
  }
}

}  // namespace igac
