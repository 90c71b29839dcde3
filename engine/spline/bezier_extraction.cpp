// SPDX-License-Identifier: BSD-3-Clause
#include "engine/spline/bezier_extraction.hpp"

#include "engine/spline/rational_basis.hpp"

#include <cmath>
#include <fmt/format.h>

#include "engine/spline/refinement.hpp"

namespace igac {

void bernstein(int p, double s, double* values, double* derivs) {
  // de Casteljau-style triangle: B^k_i = (1-s) B^{k-1}_i + s B^{k-1}_{i-1}.
  // The degree p-1 row gives the derivatives: B'^p_i = p (B^{p-1}_{i-1} - B^{p-1}_i).
  double b[32];
  if (p > 30) throw SplineError(fmt::format("Bezier degree {} is above the supported 30", p));
  b[0] = 1.0;
  for (int k = 1; k <= p; ++k) {
    if (k == p && derivs)
      for (int i = 0; i <= p; ++i)
        derivs[i] = p * ((i > 0 ? b[i - 1] : 0.0) - (i < p ? b[i] : 0.0));
    b[k] = s * b[k - 1];
    for (int i = k - 1; i > 0; --i) b[i] = (1 - s) * b[i] + s * b[i - 1];
    b[0] = (1 - s) * b[0];
  }
  if (p == 0 && derivs) derivs[0] = 0.0;
  for (int i = 0; i <= p; ++i) values[i] = b[i];
}

Eigen::VectorXd BezierElement::parameter(const Eigen::VectorXd& s) const {
  Eigen::VectorXd xi(s.size());
  for (int d = 0; d < s.size(); ++d) xi[d] = lower[d] + s[d] * (upper[d] - lower[d]);
  return xi;
}

BezierMesh::BezierMesh(const NurbsPatch& patch, const std::vector<Eigen::MatrixXd>& fields) {
  param_dim_ = patch.param_dim();
  space_dim_ = patch.space_dim();
  for (const auto& f : fields)
    if (f.rows() != patch.num_control_points())
      throw SplineError(fmt::format("Bezier extraction: a field has {} rows for {} control points", f.rows(),
                                    patch.num_control_points()));

  // Raise every interior breakpoint to multiplicity >= p.
  RefinedPatch r{patch, fields};
  for (int d = 0; d < param_dim_; ++d) {
    const KnotVector& kv = r.patch.knots(d);
    const int p = kv.degree();
    const auto b = kv.breakpoints();
    const auto m = kv.multiplicities();
    std::vector<double> add;
    for (size_t j = 1; j + 1 < b.size(); ++j)
      for (int k = m[j]; k < p; ++k) add.push_back(b[j]);
    if (!add.empty()) r = insert_knots(r.patch, d, add, r.fields);
  }
  const NurbsPatch& q = r.patch;

  std::array<std::vector<int>, 3> spans;
  std::array<int, 3> n_el{1, 1, 1};
  for (int d = 0; d < param_dim_; ++d) {
    degree_[d] = q.degree(d);
    spans[d] = q.knots(d).element_spans();
    n_el[d] = int(spans[d].size());
  }
  num_local_ = (degree_[0] + 1) * (degree_[1] + 1) * (degree_[2] + 1);

  elements_.reserve(size_t(n_el[0]) * n_el[1] * n_el[2]);
  for (int k = 0; k < n_el[2]; ++k)
    for (int j = 0; j < n_el[1]; ++j)
      for (int i = 0; i < n_el[0]; ++i) {
        BezierElement el;
        el.index = {i, j, k};
        for (int d = 0; d < param_dim_; ++d) {
          const int s = spans[d][el.index[d]];
          el.lower[d] = q.knots(d)[s];
          el.upper[d] = q.knots(d)[s + 1];
        }
        el.points.resize(num_local_, space_dim_);
        el.weights.resize(num_local_);
        el.fields.resize(r.fields.size());
        for (size_t f = 0; f < r.fields.size(); ++f) el.fields[f].resize(num_local_, r.fields[f].cols());
        for (int c = 0; c <= degree_[2]; ++c)
          for (int b = 0; b <= degree_[1]; ++b)
            for (int a = 0; a <= degree_[0]; ++a) {
              std::array<int, 3> g{0, 0, 0};
              const std::array<int, 3> loc{a, b, c};
              for (int d = 0; d < param_dim_; ++d) g[d] = spans[d][el.index[d]] - degree_[d] + loc[d];
              const int A = q.index(g), l = local_index(a, b, c);
              el.points.row(l) = q.points().row(A);
              el.weights[l] = q.weights()[A];
              for (size_t f = 0; f < r.fields.size(); ++f) el.fields[f].row(l) = r.fields[f].row(A);
            }
        elements_.push_back(std::move(el));
      }
}

void BezierMesh::basis(const BezierElement& el, const Eigen::VectorXd& s, Eigen::VectorXd& R,
                       Eigen::MatrixXd* dR) const {
  double v[3][32], dv[3][32];
  for (int d = 0; d < 3; ++d) {
    if (d < param_dim_) {
      bernstein(degree_[d], s[d], v[d], dv[d]);
    } else {
      v[d][0] = 1.0;
      dv[d][0] = 0.0;
    }
  }
  R.resize(num_local_);
  thread_local std::vector<double> drv;  // (no allocation per point: the stress recovery calls this per Gauss point)
  drv.resize(dR ? size_t(num_local_) * param_dim_ : 0);
  const int np[3] = {degree_[0] + 1, degree_[1] + 1, degree_[2] + 1};
  const double* N[3] = {v[0], v[1], v[2]};
  const double* dN[3] = {dv[0], dv[1], dv[2]};
  rational_basis_values(param_dim_, np, N, dN, el.weights.data(), R.data(), dR ? drv.data() : nullptr);
  if (dR) {
    dR->resize(num_local_, param_dim_);
    for (int l = 0; l < num_local_; ++l)
      for (int d = 0; d < param_dim_; ++d) (*dR)(l, d) = drv[size_t(l) * param_dim_ + d];
  }
}

Eigen::VectorXd BezierMesh::point(int e, const Eigen::VectorXd& s) const {
  Eigen::VectorXd R;
  basis(elements_[e], s, R);
  return elements_[e].points.transpose() * R;
}

Eigen::VectorXd BezierMesh::field(int e, int f, const Eigen::VectorXd& s) const {
  Eigen::VectorXd R;
  basis(elements_[e], s, R);
  return elements_[e].fields[f].transpose() * R;
}

void BezierMesh::append(const BezierMesh& other) {
  if (elements_.empty()) {
    *this = other;
    return;
  }
  if (other.param_dim_ != param_dim_ || other.space_dim_ != space_dim_ || other.degree_ != degree_)
    throw SplineError("Bezier meshes of different dimensions or degrees cannot be joined");
  elements_.insert(elements_.end(), other.elements_.begin(), other.elements_.end());
}

}  // namespace igac
