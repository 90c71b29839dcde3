// SPDX-License-Identifier: BSD-3-Clause
#include "engine/linear_static.hpp"

#include <algorithm>
#include <numeric>

#include <Eigen/QR>
#include <Eigen/SVD>

namespace igac {

RigidModes free_rigid_modes(const Body& body, const DofMap& dofs) {
  const int dim = body.space_dim(), n_cp = body.num_control_points();
  // An axisymmetric body (revolved patches) has one: the translation along
  // the axis (a radial motion strains the hoop, a rotation leaves the axis).
  const bool revolved = body.num_patches() > 0 && body.patch(0).revolved();
  const int per_body = revolved ? 1 : dim == 2 ? 3 : 6;
  // Each body (group of joined patches) moves rigidly on its own.
  // (Body::parts labels each part by its smallest patch: numbered here 0, 1, ...)
  std::vector<int> component_of_patch = body.parts(), number(body.num_patches(), -1);
  int n_bodies = 0;
  for (int& c : component_of_patch) c = number[c] < 0 ? (number[c] = n_bodies++) : number[c];
  n_bodies = std::max(n_bodies, 1);
  std::vector<int> component(n_cp, 0);
  for (int k = 0; k < body.num_patches(); ++k)
    for (int a : body.body_cps(k)) component[a] = component_of_patch[k];
  std::vector<Eigen::RowVectorXd> centre(n_bodies, Eigen::RowVectorXd::Zero(dim));
  std::vector<int> count(n_bodies, 0);
  for (int a = 0; a < n_cp; ++a) centre[component[a]] += body.points().row(a), ++count[component[a]];
  for (int b = 0; b < n_bodies; ++b) centre[b] /= std::max(count[b], 1);
  const int n_modes = per_body * n_bodies;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n_cp * dim, n_modes);
  for (int a = 0; a < n_cp; ++a) {
    const int c0 = per_body * component[a];
    const Eigen::RowVectorXd x = body.points().row(a) - centre[component[a]];
    if (revolved) {
      M(a * 2 + 1, c0) = 1.0;
      continue;
    }
    for (int i = 0; i < dim; ++i) M(a * dim + i, c0 + i) = 1.0;
    if (dim == 2) {
      M(a * 2 + 0, c0 + 2) = -x[1];
      M(a * 2 + 1, c0 + 2) = x[0];
    } else {  // rotations about x, y, z
      M(a * 3 + 1, c0 + 3) = -x[2]; M(a * 3 + 2, c0 + 3) = x[1];
      M(a * 3 + 0, c0 + 4) = x[2];  M(a * 3 + 2, c0 + 4) = -x[0];
      M(a * 3 + 0, c0 + 5) = -x[1]; M(a * 3 + 1, c0 + 5) = x[0];
    }
  }
  std::vector<int> fixed;
  for (int i = 0; i < dofs.num_dofs(); ++i)
    if (dofs.equation(i) < 0) fixed.push_back(i);
  Eigen::MatrixXd null_basis;
  if (fixed.empty()) {
    null_basis = Eigen::MatrixXd::Identity(n_modes, n_modes);
  } else {
    Eigen::MatrixXd Mf(fixed.size(), n_modes);
    for (size_t r = 0; r < fixed.size(); ++r) Mf.row(r) = M.row(fixed[r]);
    // The rank is judged with the rotations in units of the body's size (a
    // rotation's column is in lengths, a translation's is 1): a held body in
    // small units (a wall 1e-10 thick, 1e-7 long) is held.  When that agrees
    // with the unscaled rank, the basis is the unscaled one, as before.
    const auto rank_of = [](const Eigen::VectorXd& s) {
      const double tol = 1e-10 * std::max(1.0, s.size() ? s[0] : 1.0);
      int rank = 0;
      while (rank < s.size() && s[rank] > tol) ++rank;
      return rank;
    };
    Eigen::VectorXd scale = Eigen::VectorXd::Ones(n_modes);
    const double size = (body.points().colwise().maxCoeff() - body.points().colwise().minCoeff()).maxCoeff();
    if (size > 0)  // each body's columns: dim translations, then its rotations
      for (int b = 0; b < n_bodies; ++b) scale.segment(per_body * b + dim, per_body - dim).setConstant(1 / size);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(Mf, Eigen::ComputeFullV);
    Eigen::JacobiSVD<Eigen::MatrixXd> scaled(Mf * scale.asDiagonal(), Eigen::ComputeFullV);
    const int rank = rank_of(scaled.singularValues());
    null_basis = rank == rank_of(svd.singularValues())
                     ? Eigen::MatrixXd(svd.matrixV().rightCols(n_modes - rank))
                     : Eigen::MatrixXd(scale.asDiagonal() * scaled.matrixV().rightCols(n_modes - rank));
  }
  RigidModes r;
  const int k = int(null_basis.cols());
  Eigen::MatrixXd R(dofs.num_free(), k);
  for (int i = 0; i < dofs.num_dofs(); ++i)
    if (dofs.equation(i) >= 0) R.row(dofs.equation(i)) = M.row(i) * null_basis;
  if (k > 0) {
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(R);
    r.modes = qr.householderQ() * Eigen::MatrixXd::Identity(R.rows(), k);
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> piv(r.modes.transpose());
    for (int j = 0; j < k; ++j) r.pinned.push_back(int(piv.colsPermutation().indices()[j]));
  } else {
    r.modes.resize(dofs.num_free(), 0);
  }
  return r;
}

Eigen::SparseMatrix<double> pin_equations(const Eigen::SparseMatrix<double>& K, const std::vector<int>& pinned) {
  if (pinned.empty()) return K;
  std::vector<char> is_pinned(K.rows(), 0);
  for (int p : pinned) is_pinned[p] = 1;
  Eigen::SparseMatrix<double> A = K;
  for (int c = 0; c < A.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it)
      if (is_pinned[it.row()] || is_pinned[it.col()]) it.valueRef() = (it.row() == it.col()) ? 1.0 : 0.0;
  return A;
}

}  // namespace igac
