// SPDX-License-Identifier: BSD-3-Clause
#include "engine/volumetric_projection.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <limits>

namespace igac {

std::optional<Formulation> parse_formulation(std::string_view name) {
  if (name == "displacement") return Formulation::displacement;
  if (name == "mixed") return Formulation::mixed;
  if (name == "mixed_element") return Formulation::mixed_element;
  return std::nullopt;
}

std::string_view formulation_name(Formulation f) {
  switch (f) {
    case Formulation::mixed: return "mixed";
    case Formulation::mixed_element: return "mixed_element";
    case Formulation::displacement: break;
  }
  return "displacement";
}

// Constants per Bezier element, whatever p.  A C^{p-1} spline displacement
// has about dim unknowns per element, so an element-local space of more than
// one mode per element over-constrains it: Q_{p-1} (4 modes per 2D element at
// p = 2) still locks, measured on the Lame cylinder at nu = 0.49999 (4 x 8
// elements: L2 error 76 times the nu = 0.3 one, against 1.25 times with
// constants).  Constants are the local counterpart of Elguedj et al.'s
// S^{p-1}_{p-2} (one unknown per element too); the price is a first-order
// pressure (docs/design.md).
int pressure_degree(int displacement_degree) {
  static_cast<void>(displacement_degree);
  return 0;
}

double stabilisation_modulus(const HyperelasticLaw& law, int dim) {
  if (!law.has_volumetric_split()) return 0.0;
  if (dim == 2) {
    Eigen::Matrix2d P;
    Eigen::Matrix4d A;
    return law.evaluate_isochoric(Eigen::Matrix2d::Identity(), P, &A) ? A(1, 1) : 0.0;
  }
  Eigen::Matrix3d P;
  Eigen::Matrix<double, 9, 9> A;
  return law.evaluate_isochoric(Eigen::Matrix3d::Identity(), P, &A) ? A(1, 1) : 0.0;
}

void add_volumetric_tangent(const Eigen::MatrixXd& Pi, const std::vector<double>& JxW, const Eigen::VectorXd& d2U,
                            double mu_s, const Eigen::MatrixXd& B, Eigen::MatrixXd& Bbar, Eigen::MatrixXd& Ke) {
  const Eigen::Map<const Eigen::VectorXd> w(JxW.data(), Eigen::Index(JxW.size()));
  Bbar.noalias() = Pi * B;
  const Eigen::VectorXd bar = w.cwiseProduct((d2U.array() - mu_s).matrix());
  Ke.noalias() += Bbar.transpose() * bar.asDiagonal() * Bbar;
  if (mu_s != 0.0) Ke.noalias() += mu_s * (B.transpose() * w.asDiagonal() * B);
}

template <int pd>
void ElementProjection::build(const std::vector<Eigen::Matrix<double, pd, 1>>& xi, const std::vector<double>& JxW,
                              int degree) {
  const int nq = int(xi.size());
  int np = 1;
  for (int d = 0; d < pd; ++d) np *= degree + 1;
  // centre and half-width of the element in each parametric direction
  Eigen::Matrix<double, pd, 1> lo = Eigen::Matrix<double, pd, 1>::Constant(std::numeric_limits<double>::infinity());
  Eigen::Matrix<double, pd, 1> hi = -lo;
  for (const auto& x : xi) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const Eigen::Matrix<double, pd, 1> c = (lo + hi) / 2;
  const Eigen::Matrix<double, pd, 1> h = ((hi - lo) / 2).cwiseMax(std::numeric_limits<double>::min());
  phi_.resize(nq, np);
  for (int q = 0; q < nq; ++q)
    for (int m = 0; m < np; ++m) {
      double v = 1;
      for (int d = 0, rest = m; d < pd; ++d, rest /= degree + 1) {
        const double s = (xi[q][d] - c[d]) / h[d];
        for (int e = 0; e < rest % (degree + 1); ++e) v *= s;
      }
      phi_(q, m) = v;
    }
  const Eigen::Map<const Eigen::VectorXd> w(JxW.data(), nq);
  gram_.noalias() = phi_.transpose() * w.asDiagonal() * phi_;
  // Pi = Phi M^{-1} (W Phi)^T
  const Eigen::MatrixXd rhs = (w.asDiagonal() * phi_).transpose();
  pi_.noalias() = phi_ * gram_.llt().solve(rhs);
}

template void ElementProjection::build<2>(const std::vector<Eigen::Matrix<double, 2, 1>>&, const std::vector<double>&,
                                          int);
template void ElementProjection::build<3>(const std::vector<Eigen::Matrix<double, 3, 1>>&, const std::vector<double>&,
                                          int);

}  // namespace igac
