// SPDX-License-Identifier: BSD-3-Clause
#include "engine/spline/nurbs_patch.hpp"

#include "engine/spline/rational_basis.hpp"

#include <cmath>
#include <fmt/format.h>

namespace igac {

NurbsPatch::NurbsPatch(std::vector<KnotVector> knots, Eigen::MatrixXd points,
                       Eigen::VectorXd weights)
    : knots_(std::move(knots)), points_(std::move(points)), weights_(std::move(weights)) {
  if (knots_.empty() || knots_.size() > 3)
    throw SplineError(fmt::format("a patch has 1 to 3 parametric directions, got {}", knots_.size()));
  int n = 1;
  for (const auto& k : knots_) n *= k.num_basis();
  if (points_.rows() != n || weights_.size() != n)
    throw SplineError(fmt::format("the knot vectors need {} control points, got {} points and {} weights",
                                  n, points_.rows(), weights_.size()));
  for (int i = 0; i < n; ++i) {
    if (!(weights_[i] > 0) || !std::isfinite(weights_[i]))
      throw SplineError(fmt::format("weight {} of control point {} is not positive", weights_[i], i));
    if (!points_.row(i).allFinite())
      throw SplineError(fmt::format("control point {} is not finite", i));
  }
}

int NurbsPatch::num_elements() const {
  int n = 1;
  for (const auto& k : knots_) n *= k.num_elements();
  return n;
}

std::array<int, 3> NurbsPatch::multi_index(int i) const {
  std::array<int, 3> m{0, 0, 0};
  for (int d = 0; d < param_dim(); ++d) {
    m[d] = i % num_basis(d);
    i /= num_basis(d);
  }
  return m;
}

void NurbsPatch::rational_basis(const Eigen::VectorXd& xi, std::vector<int>& indices,
                                Eigen::VectorXd& values, Eigen::MatrixXd& derivs) const {
  const int pd = param_dim();
  std::array<std::vector<std::vector<double>>, 3> b;
  std::array<int, 3> span{0, 0, 0}, np{1, 1, 1};
  for (int d = 0; d < pd; ++d) {
    span[d] = knots_[d].find_span(xi[d]);
    knots_[d].basis_derivatives(span[d], xi[d], 1, b[d]);
    np[d] = degree(d) + 1;
  }
  const int n = np[0] * np[1] * np[2];
  indices.resize(n);
  values.resize(n);
  std::vector<double> w(n), dR(size_t(n) * pd);
  for (int a = 0; a < n; ++a) {
    const std::array<int, 3> loc{a % np[0], (a / np[0]) % np[1], a / (np[0] * np[1])};
    std::array<int, 3> gi{0, 0, 0};
    for (int d = 0; d < pd; ++d) gi[d] = span[d] - degree(d) + loc[d];
    indices[a] = index(gi);
    w[a] = weights_[indices[a]];
  }
  std::array<const double*, 3> N{}, dN{};
  for (int d = 0; d < pd; ++d) {
    N[d] = b[d][0].data();
    dN[d] = b[d][1].data();
  }
  rational_basis_values(pd, np.data(), N.data(), dN.data(), w.data(), values.data(), dR.data());
  derivs.resize(n, pd);
  for (int a = 0; a < n; ++a)
    for (int d = 0; d < pd; ++d) derivs(a, d) = dR[size_t(a) * pd + d];
}

Eigen::VectorXd NurbsPatch::field(const Eigen::MatrixXd& coefs, const Eigen::VectorXd& xi,
                                  Eigen::MatrixXd* dfield) const {
  std::vector<int> idx;
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  rational_basis(xi, idx, N, dN);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(coefs.cols());
  if (dfield) dfield->setZero(coefs.cols(), param_dim());
  for (size_t a = 0; a < idx.size(); ++a) {
    v += N[a] * coefs.row(idx[a]).transpose();
    if (dfield) *dfield += coefs.row(idx[a]).transpose() * dN.row(a);
  }
  return v;
}

Eigen::VectorXd NurbsPatch::point(const Eigen::VectorXd& xi) const { return field(points_, xi); }

Eigen::MatrixXd NurbsPatch::jacobian(const Eigen::VectorXd& xi) const {
  Eigen::MatrixXd J;
  field(points_, xi, &J);
  return J;
}

Eigen::MatrixXd NurbsPatch::second_derivatives(const Eigen::VectorXd& xi) const {
  const int pd = param_dim(), sd = space_dim();
  std::array<std::vector<std::vector<double>>, 3> b;
  std::array<int, 3> span{0, 0, 0}, np{1, 1, 1};
  for (int d = 0; d < pd; ++d) {
    span[d] = knots_[d].find_span(xi[d]);
    knots_[d].basis_derivatives(span[d], xi[d], 2, b[d]);
    np[d] = degree(d) + 1;
  }
  // homogeneous sums: A (point times weight) and W, with their first and second derivatives
  Eigen::VectorXd A = Eigen::VectorXd::Zero(sd);
  Eigen::MatrixXd dA = Eigen::MatrixXd::Zero(sd, pd), ddA = Eigen::MatrixXd::Zero(sd, pd * pd);
  double W = 0;
  Eigen::VectorXd dW = Eigen::VectorXd::Zero(pd), ddW = Eigen::VectorXd::Zero(pd * pd);
  const int n = np[0] * np[1] * np[2];
  for (int a = 0; a < n; ++a) {
    const std::array<int, 3> loc{a % np[0], (a / np[0]) % np[1], a / (np[0] * np[1])};
    std::array<int, 3> gi{0, 0, 0};
    for (int d = 0; d < pd; ++d) gi[d] = span[d] - degree(d) + loc[d];
    const int i = index(gi);
    // d^k/dxi of the tensor product with order[d] derivatives in direction d
    auto product = [&](const std::array<int, 3>& order) {
      double v = weights_[i];
      for (int d = 0; d < pd; ++d) v *= b[d][order[d]][loc[d]];
      return v;
    };
    const double v = product({0, 0, 0});
    A += v * points_.row(i).transpose();
    W += v;
    for (int p = 0; p < pd; ++p) {
      std::array<int, 3> o{0, 0, 0};
      ++o[p];
      const double dv = product(o);
      dA.col(p) += dv * points_.row(i).transpose();
      dW[p] += dv;
      for (int q = 0; q < pd; ++q) {
        std::array<int, 3> oo = o;
        ++oo[q];
        const double ddv = product(oo);
        ddA.col(p * pd + q) += ddv * points_.row(i).transpose();
        ddW[p * pd + q] += ddv;
      }
    }
  }
  const Eigen::VectorXd X = A / W;
  Eigen::MatrixXd dX(sd, pd);
  for (int p = 0; p < pd; ++p) dX.col(p) = (dA.col(p) - dW[p] * X) / W;
  Eigen::MatrixXd out(sd, pd * pd);
  for (int p = 0; p < pd; ++p)
    for (int q = 0; q < pd; ++q)
      out.col(p * pd + q) = (ddA.col(p * pd + q) - ddW[p * pd + q] * X - dW[p] * dX.col(q) - dW[q] * dX.col(p)) / W;
  return out;
}

std::vector<int> NurbsPatch::face_control_points(const Face& f) const {
  std::vector<int> out;
  const int fixed = f.at_end ? num_basis(f.direction) - 1 : 0;
  for (int i = 0; i < num_control_points(); ++i)
    if (multi_index(i)[f.direction] == fixed) out.push_back(i);
  return out;  // increasing global index == face numbering, first free direction fastest
}

NurbsPatch NurbsPatch::face_patch(const Face& f) const {
  if (param_dim() < 2) throw SplineError("a curve has no faces of positive dimension");
  std::vector<KnotVector> k;
  for (int d = 0; d < param_dim(); ++d)
    if (d != f.direction) k.push_back(knots_[d]);
  const auto cps = face_control_points(f);
  Eigen::MatrixXd P(cps.size(), space_dim());
  Eigen::VectorXd w(cps.size());
  for (size_t a = 0; a < cps.size(); ++a) {
    P.row(a) = points_.row(cps[a]);
    w[a] = weights_[cps[a]];
  }
  NurbsPatch face(std::move(k), std::move(P), std::move(w));
  face.revolved_ = revolved_;
  return face;
}

void NurbsPatch::set_revolved(bool revolved) {
  if (revolved && space_dim() != 2) throw SplineError("only a patch in 2D (r, z) can be revolved about an axis");
  const double size = points_.rows() > 0 ? (points_.colwise().maxCoeff() - points_.colwise().minCoeff()).norm() : 0;
  if (revolved && points_.rows() > 0 && points_.col(0).minCoeff() < -1e-10 * size)
    throw SplineError(fmt::format("a revolved patch lies at r = x >= 0 (a control point is at x = {:.6g})",
                                  points_.col(0).minCoeff()));
  revolved_ = revolved;
}

Eigen::VectorXd face_area_vector(const Face& f, const Eigen::MatrixXd& T) {
  const double s = f.at_end ? 1.0 : -1.0;
  if (T.rows() == 2) {
    // 2D: cof(J) e_0 = (b1, -b0) with b = dX/dxi1; cof(J) e_1 = (-a1, a0), a = dX/dxi0.
    const Eigen::Vector2d t = T.col(0);
    return f.direction == 0 ? Eigen::Vector2d(s * t[1], -s * t[0]).eval()
                            : Eigen::Vector2d(-s * t[1], s * t[0]).eval();
  }
  const Eigen::Vector3d t0 = T.col(0), t1 = T.col(1);
  // In-face directions keep their order: d=0 -> (1,2), d=1 -> (0,2), d=2 -> (0,1).
  // cof(J) e_0 = b x c, e_1 = c x a, e_2 = a x b.
  const Eigen::Vector3d n = f.direction == 1 ? Eigen::Vector3d(t1.cross(t0)) : Eigen::Vector3d(t0.cross(t1));
  return s * n;
}

}  // namespace igac
