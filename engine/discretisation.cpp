// SPDX-License-Identifier: BSD-3-Clause
#include "engine/discretisation.hpp"

#include "engine/spline/rational_basis.hpp"

#include <Eigen/LU>
#include <limits>
#include <fmt/format.h>

namespace igac {

UnivariateTable tabulate(const KnotVector& kv, const GaussRule& rule) {
  UnivariateTable t;
  t.degree = kv.degree();
  t.n_points = int(rule.points.size());
  t.span = kv.element_spans();
  const int p1 = t.degree + 1;
  std::vector<std::vector<double>> b;
  for (int s : t.span) {
    const double a = kv[s], h = kv[s + 1] - kv[s];
    for (int q = 0; q < t.n_points; ++q) {
      const double x = a + h * rule.points[q];
      t.xi.push_back(x);
      t.weight.push_back(h * rule.weights[q]);
      kv.basis_derivatives(s, x, 1, b);
      for (int j = 0; j < p1; ++j) {
        t.value.push_back(b[0][j]);
        t.deriv.push_back(b[1][j]);
      }
    }
  }
  return t;
}

PatchQuadrature::PatchQuadrature(const NurbsPatch& patch, int points, std::optional<Face> face,
                                 std::vector<int> parent_cps)
    : patch_(patch), face_(face), parent_cps_(std::move(parent_cps)) {
  const GaussRule rule = gauss_legendre(points);
  for (int d = 0; d < patch_.param_dim(); ++d) {
    tables_[d] = tabulate(patch_.knots(d), rule);
    n_el_[d] = int(tables_[d].span.size());
  }
  if (face_ && patch_.param_dim() != patch_.space_dim() - 1)
    throw SplineError("a face quadrature needs a patch of one dimension less than space");
}

int PatchQuadrature::num_points() const {
  int n = 1;
  for (int d = 0; d < patch_.param_dim(); ++d) n *= tables_[d].n_points;
  return n;
}

int PatchQuadrature::num_local() const {
  int n = 1;
  for (int d = 0; d < patch_.param_dim(); ++d) n *= tables_[d].degree + 1;
  return n;
}

std::array<int, 3> PatchQuadrature::element_index(int e) const {
  return {e % n_el_[0], (e / n_el_[0]) % n_el_[1], e / (n_el_[0] * n_el_[1])};
}

void PatchQuadrature::control_points(int e, std::vector<int>& cps, std::vector<int>* own) const {
  const int pd = patch_.param_dim();
  const auto ei = element_index(e);
  std::array<int, 3> np{1, 1, 1};
  for (int d = 0; d < pd; ++d) np[d] = tables_[d].degree + 1;
  const int n_loc = np[0] * np[1] * np[2];
  cps.resize(n_loc);
  if (own) own->resize(n_loc);
  for (int a = 0; a < n_loc; ++a) {
    const std::array<int, 3> loc{a % np[0], (a / np[0]) % np[1], a / (np[0] * np[1])};
    std::array<int, 3> gi{0, 0, 0};
    for (int d = 0; d < pd; ++d) gi[d] = tables_[d].span[ei[d]] - tables_[d].degree + loc[d];
    const int i = patch_.index(gi);
    cps[a] = parent_cps_.empty() ? i : parent_cps_[i];
    if (own) (*own)[a] = i;
  }
}

template <int pd, int sd>
void PatchQuadrature::evaluate(int e, ElementValues<pd, sd>& out, bool gradients) const {
  if (patch_.param_dim() != pd || patch_.space_dim() != sd)
    throw SplineError(fmt::format("element values of a {}-in-{}D element asked of a {}-in-{}D patch", pd, sd,
                                  patch_.param_dim(), patch_.space_dim()));
  constexpr bool face = pd < sd;
  if (face && !face_) throw SplineError("face element values need the face of the parent patch");
  const auto ei = element_index(e);
  std::array<int, pd> np, nq;
  int n_loc = 1, n_q = 1;
  for (int d = 0; d < pd; ++d) {
    np[d] = tables_[d].degree + 1;
    nq[d] = tables_[d].n_points;
    n_loc *= np[d];
    n_q *= nq[d];
  }
  out.n_loc = n_loc;
  out.n_q = n_q;
  out.revolved = patch_.revolved();
  thread_local std::vector<int> own;
  control_points(e, out.cps, &own);
  out.X_cp.resize(n_loc);
  out.w_cp.resize(n_loc);
  for (int a = 0; a < n_loc; ++a) {
    out.w_cp[a] = patch_.weights()[own[a]];
    out.X_cp[a] = patch_.points().row(own[a]).transpose();
  }
  out.R.resize(size_t(n_q) * n_loc);
  out.dR_dxi.resize(size_t(n_q) * n_loc * pd);
  out.dR_dX.resize(gradients && !face ? size_t(n_q) * n_loc * sd : 0);
  out.X.resize(n_q);
  out.xi.resize(n_q);
  out.w.resize(n_q);
  out.JxW.resize(n_q);
  out.normal.resize(face ? n_q : 0);
  out.min_det_J = std::numeric_limits<double>::infinity();
  const double sigma = face ? face_orientation(*face_, sd) : 0.0;

  for (int q = 0; q < n_q; ++q) {
    std::array<const double*, pd> Nd, dNd;
    double wq = 1;
    for (int d = 0, r = q; d < pd; ++d) {  // q = q0 + nq0 (q1 + nq1 q2)
      const int row = ei[d] * nq[d] + r % nq[d];
      r /= nq[d];
      wq *= tables_[d].weight[row];
      out.xi[q][d] = tables_[d].xi[row];
      Nd[d] = tables_[d].value.data() + size_t(row) * np[d];
      dNd[d] = tables_[d].deriv.data() + size_t(row) * np[d];
    }
    double* R = out.R.data() + size_t(q) * n_loc;
    double* dR = out.dR_dxi.data() + size_t(q) * n_loc * pd;
    rational_basis_values<pd>(np.data(), Nd.data(), dNd.data(), out.w_cp.data(), R, dR);
    Eigen::Matrix<double, sd, 1> X = Eigen::Matrix<double, sd, 1>::Zero();
    Eigen::Matrix<double, sd, pd> J = Eigen::Matrix<double, sd, pd>::Zero();  // dX/dxi
    for (int a = 0; a < n_loc; ++a) {
      X += R[a] * out.X_cp[a];
      for (int d = 0; d < pd; ++d) J.col(d) += dR[a * pd + d] * out.X_cp[a];
    }
    out.X[q] = X;
    out.w[q] = wq;
    const double ring = patch_.ring_length(X);  // 2 pi r on a revolved patch
    if constexpr (face) {
      const Eigen::Matrix<double, sd, 1> nA = oriented_area<sd>(sigma, J);
      const double dA = nA.norm();
      out.normal[q] = nA / dA;
      out.JxW[q] = dA * wq * ring;
    } else {
      const double det = J.determinant();  // closed forms for 2x2 and 3x3
      out.min_det_J = std::min(out.min_det_J, det);
      out.JxW[q] = det * wq * ring;
      if (!gradients) continue;
      const Eigen::Matrix<double, sd, sd> Jinv = J.inverse();
      double* dN = out.dR_dX.data() + size_t(q) * n_loc * sd;
      for (int a = 0; a < n_loc; ++a)
        for (int c = 0; c < sd; ++c) {  // dN_a/dX_c = sum_d dR_a/dxi_d (J^{-1})_dc
          double s = 0;
          for (int d = 0; d < sd; ++d) s += dR[a * sd + d] * Jinv(d, c);
          dN[a * sd + c] = s;
        }
    }
  }
}

template void PatchQuadrature::evaluate<1, 2>(int, ElementValues<1, 2>&, bool) const;
template void PatchQuadrature::evaluate<2, 2>(int, ElementValues<2, 2>&, bool) const;
template void PatchQuadrature::evaluate<2, 3>(int, ElementValues<2, 3>&, bool) const;
template void PatchQuadrature::evaluate<3, 3>(int, ElementValues<3, 3>&, bool) const;

namespace {

// ElementData (run-time sizes) from the fixed-size values.
template <int pd, int sd>
void copy_values(const ElementValues<pd, sd>& v, bool gradients, ElementData& out) {
  const int n_loc = v.n_loc, n_q = v.n_q;
  out.cps = v.cps;
  out.revolved = v.revolved;
  out.N.resize(n_q, n_loc);
  out.X.resize(n_q, sd);
  out.xi.resize(n_q, pd);
  out.JxW.resize(n_q);
  for (int q = 0; q < n_q; ++q) {
    for (int a = 0; a < n_loc; ++a) out.N(q, a) = v.N(q, a);
    out.X.row(q) = v.X[q].transpose();
    out.xi.row(q) = v.xi[q].transpose();
    out.JxW[q] = v.JxW[q];
  }
  if constexpr (pd < sd) {
    out.normal.resize(n_q, sd);
    for (int q = 0; q < n_q; ++q) out.normal.row(q) = v.normal[q].transpose();
  } else if (gradients) {
    out.dN.resize(n_q);
    for (int q = 0; q < n_q; ++q) {
      out.dN[q].resize(n_loc, sd);
      const double* g = v.gradients(q);
      for (int a = 0; a < n_loc; ++a)
        for (int c = 0; c < sd; ++c) out.dN[q](a, c) = g[a * sd + c];
    }
  }
  out.min_det_J = v.min_det_J;
}

template <int pd, int sd>
void evaluate_into(const PatchQuadrature& quad, int e, bool gradients, ElementData& out) {
  thread_local ElementValues<pd, sd> v;
  quad.evaluate(e, v, gradients);
  copy_values(v, gradients, out);
}

}  // namespace

void PatchQuadrature::evaluate(int e, ElementData& out, bool gradients) const {
  const int pd = patch_.param_dim(), sd = patch_.space_dim();
  if (pd == 2 && sd == 2) evaluate_into<2, 2>(*this, e, gradients, out);
  else if (pd == 3 && sd == 3) evaluate_into<3, 3>(*this, e, gradients, out);
  else if (pd == 1 && sd == 2) evaluate_into<1, 2>(*this, e, gradients, out);
  else if (pd == 2 && sd == 3) evaluate_into<2, 3>(*this, e, gradients, out);
  else
    throw SplineError(fmt::format("no element values for a {}-parameter patch in {}D", pd, sd));
}

}  // namespace igac
