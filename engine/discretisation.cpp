#include "engine/discretisation.hpp"

#include "engine/spline/rational_basis.hpp"

#include <Eigen/LU>
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

void PatchQuadrature::control_points(int e, std::vector<int>& cps) const {
  const int pd = patch_.param_dim();
  const auto ei = element_index(e);
  std::array<int, 3> np{1, 1, 1};
  for (int d = 0; d < pd; ++d) np[d] = tables_[d].degree + 1;
  cps.resize(np[0] * np[1] * np[2]);
  for (int a = 0; a < int(cps.size()); ++a) {
    const std::array<int, 3> loc{a % np[0], (a / np[0]) % np[1], a / (np[0] * np[1])};
    std::array<int, 3> gi{0, 0, 0};
    for (int d = 0; d < pd; ++d) gi[d] = tables_[d].span[ei[d]] - tables_[d].degree + loc[d];
    const int own = patch_.index(gi);
    cps[a] = parent_cps_.empty() ? own : parent_cps_[own];
  }
}

void PatchQuadrature::evaluate(int e, ElementData& out, bool gradients) const {
  const int pd = patch_.param_dim(), sd = patch_.space_dim();
  const auto ei = element_index(e);
  std::array<int, 3> np{1, 1, 1}, nq{1, 1, 1};
  for (int d = 0; d < pd; ++d) {
    np[d] = tables_[d].degree + 1;
    nq[d] = tables_[d].n_points;
  }
  const int n_loc = np[0] * np[1] * np[2], n_q = nq[0] * nq[1] * nq[2];
  out.cps.resize(n_loc);
  out.N.resize(n_q, n_loc);
  out.X.resize(n_q, sd);
  out.xi.resize(n_q, pd);
  out.JxW.resize(n_q);
  if (gradients) out.dN.resize(n_q);
  if (face_) out.normal.resize(n_q, sd);
  out.min_det_J = std::numeric_limits<double>::infinity();

  // local control points
  Eigen::VectorXd w(n_loc);
  Eigen::MatrixXd P(n_loc, sd);
  for (int a = 0; a < n_loc; ++a) {
    const std::array<int, 3> loc{a % np[0], (a / np[0]) % np[1], a / (np[0] * np[1])};
    std::array<int, 3> gi{0, 0, 0};
    for (int d = 0; d < pd; ++d) gi[d] = tables_[d].span[ei[d]] - tables_[d].degree + loc[d];
    const int own = patch_.index(gi);
    out.cps[a] = parent_cps_.empty() ? own : parent_cps_[own];
    w[a] = patch_.weights()[own];
    P.row(a) = patch_.points().row(own);
  }

  std::vector<double> R(n_loc), dRv(size_t(n_loc) * pd);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::Map<const RowMajor> dR(dRv.data(), n_loc, pd);  // dR_a / dxi_d
  Eigen::MatrixXd J(sd, pd);
  for (int q = 0; q < n_q; ++q) {
    const std::array<int, 3> qi{q % nq[0], (q / nq[0]) % nq[1], q / (nq[0] * nq[1])};
    double wq = 1;
    std::array<const double*, 3> Nd{}, dNd{};
    for (int d = 0; d < pd; ++d) {
      const int row = ei[d] * nq[d] + qi[d];
      wq *= tables_[d].weight[row];
      out.xi(q, d) = tables_[d].xi[row];
      Nd[d] = tables_[d].value.data() + size_t(row) * np[d];
      dNd[d] = tables_[d].deriv.data() + size_t(row) * np[d];
    }
    rational_basis_values(pd, np.data(), Nd.data(), dNd.data(), w.data(), R.data(), dRv.data());
    for (int a = 0; a < n_loc; ++a) out.N(q, a) = R[a];
    out.X.row(q) = out.N.row(q) * P;
    J.noalias() = P.transpose() * dR;  // sd x pd
    if (face_) {
      const Eigen::VectorXd nA = face_area_vector(*face_, J);
      const double dA = nA.norm();
      out.normal.row(q) = nA.transpose() / dA;
      out.JxW[q] = dA * wq;
    } else {
      // fixed-size determinant and inverse: no factorisation, no allocation
      double det;
      if (sd == 2) {
        const Eigen::Matrix2d J2 = J;
        det = J2.determinant();
        if (gradients) out.dN[q].noalias() = dR * J2.inverse();
      } else {
        const Eigen::Matrix3d J3 = J;
        det = J3.determinant();
        if (gradients) out.dN[q].noalias() = dR * J3.inverse();
      }
      out.min_det_J = std::min(out.min_det_J, det);
      out.JxW[q] = det * wq;
    }
  }
}

}  // namespace igac
