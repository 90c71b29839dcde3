// SPDX-License-Identifier: BSD-3-Clause
#include "engine/follower_pressure.hpp"

#include <algorithm>
#include <type_traits>
#include <fmt/format.h>
#include <numbers>
#include <stdexcept>

#include "engine/face_quadrature.hpp"
#include "engine/sparsity.hpp"

namespace igac {

namespace {

// d a / d u_(B,k) for a basis function with parametric derivatives dR
// (one per face direction): a is linear in each tangent, and
// d t_a / d u_(B,k) = dR_a e_k.
template <int dim>
Eigen::Matrix<double, dim, 1> area_derivative(double sigma, const Eigen::Matrix<double, dim, dim - 1>& T,
                                              const double* dR, int k) {
  Eigen::Matrix<double, dim, 1> ek = Eigen::Matrix<double, dim, 1>::Unit(k);
  if constexpr (dim == 2)
    return sigma * dR[0] * Eigen::Vector2d(ek[1], -ek[0]);
  else
    return sigma * (dR[0] * ek.cross(T.col(1)) + dR[1] * T.col(0).cross(ek));
}

// Pressure p on the faces: f_ext -= p int N_A a dxi, with a the area vector
// of the current face (u given) or of the reference face (u null); when K is
// given, K += p int N_A da/du dxi (= -d f_ext / du).  Per face point: the
// point's contribution as an element vector and matrix, then the one scatter
// (sparsity.hpp); per point rather than per element, so that f and K add
// the terms in the order they always have (the shipped results stay the
// same to the bit).  `traction` (dim entries, u and K null): instead of the
// pressure, the dead traction t per unit reference area, f += int N_A t |a| dxi.
void faces_pressure(const Body& body, const DofMap& dofs, const std::vector<PatchSide>& faces, double p,
                    const Eigen::MatrixXd* u, Eigen::VectorXd& f, Eigen::SparseMatrix<double>* K,
                    const double* traction = nullptr, const FaceElementFlags* wet = nullptr) {
  const FaceQuadrature quad(body, faces, gauss_points_for(body.degree()));
  if (wet && wet->size() != faces.size())
    throw std::invalid_argument(fmt::format("a pressure's mask has {} sides for {} faces", wet->size(), faces.size()));
  std::vector<int> eq;
  Eigen::VectorXd fe;
  Eigen::MatrixXd Ke;
  int side = -1, element = 0;  // the element's number in its side
  quad.for_each_element([&](int s, const auto& v) {
    element = s == side ? element + 1 : 0;
    side = s;
    if (wet && !(*wet)[size_t(s)].at(size_t(element))) return;
    constexpr int dim = std::remove_cvref_t<decltype(v)>::space_dim, pd = dim - 1;
    using Vec = Eigen::Matrix<double, dim, 1>;
    const double sigma = face_orientation(quad.side(s).face, dim);
    const int nl = v.n_loc, nd = nl * dim;
    dofs.element_equations(v.cps, eq);
    thread_local Eigen::Matrix<double, Eigen::Dynamic, dim> x;  // current (or reference) control points
    thread_local Eigen::Matrix<double, Eigen::Dynamic, pd> dR;  // dR_a/dxi_d at the point
    x.resize(nl, dim);
    dR.resize(nl, pd);
    for (int a = 0; a < nl; ++a) {
      x.row(a) = v.X_cp[a].transpose();
      if (u) x.row(a) += u->row(v.cps[a]);
    }
    for (int q = 0; q < v.n_q; ++q) {
      const double* dRq = v.parametric_derivatives(q);  // [a * pd + d]
      for (int a = 0; a < nl; ++a)
        for (int d = 0; d < pd; ++d) dR(a, d) = dRq[a * pd + d];
      const Eigen::Matrix<double, dim, pd> T = x.transpose() * dR;
      const Vec area = oriented_area<dim>(sigma, T);
      // axisymmetric: the face is the surface the curve sweeps, so its area
      // carries 2 pi r at the current (or reference) radius r = x_0
      double ring = 1;
      if (v.revolved) {
        double r = 0;
        for (int a = 0; a < nl; ++a) r += v.N(q, a) * x(a, 0);
        ring = 2 * std::numbers::pi * r;
      }
      const double pw = p * v.w[q] * ring;
      fe.resize(nd);
      if (traction) {
        const double aw = area.norm() * v.w[q] * ring;
        for (int a = 0; a < nl; ++a)
          for (int i = 0; i < dim; ++i) fe[a * dim + i] = aw * v.N(q, a) * traction[i];
      } else {
        for (int a = 0; a < nl; ++a)
          for (int i = 0; i < dim; ++i) fe[a * dim + i] = -(pw * v.N(q, a) * area[i]);
      }
      scatter_element_vector(eq, fe, f.data());
      if (!K) continue;
      Ke.resize(nd, nd);
      for (int b = 0; b < nl; ++b)
        for (int k = 0; k < dim; ++k) {
          const Vec da = area_derivative<dim>(sigma, T, dRq + b * pd, k);
          for (int a = 0; a < nl; ++a)
            for (int i = 0; i < dim; ++i) Ke(a * dim + i, b * dim + k) = pw * v.N(q, a) * da[i];
          if (v.revolved && k == 0)  // d(2 pi r)/du_(b, r) = 2 pi N_b
            for (int a = 0; a < nl; ++a)
              for (int i = 0; i < dim; ++i)
                Ke(a * dim + i, b * dim) += p * v.w[q] * 2 * std::numbers::pi * v.N(q, b) * v.N(q, a) * area[i];
        }
      scatter_element_matrix(*K, K->valuePtr(), eq, Ke);
    }
  });
}

void check_shapes(const Body& body, const DofMap& dofs, const Eigen::VectorXd& f) {
  const int dim = body.space_dim();
  if ((dim != 2 && dim != 3) || body.param_dim() != dim)
    throw std::invalid_argument("a pressure load needs a 2D or 3D volume body");
  if (dofs.dim() != dim || dofs.num_dofs() != body.num_control_points() * dim)
    throw std::invalid_argument("the dof map does not belong to the body of the pressure load");
  if (f.size() != dofs.num_free())
    throw std::invalid_argument(
        fmt::format("pressure load: force vector has {} entries for {} free dofs", f.size(), dofs.num_free()));
}

}  // namespace

Eigen::SparseMatrix<double> follower_pressure_pattern(const Body& body, const DofMap& dofs,
                                                      const std::vector<PatchSide>& faces) {
  const FaceQuadrature quad(body, faces, 1);  // (the elements' functions only)
  std::vector<int> eq;
  std::vector<Eigen::Triplet<double>> t;
  quad.for_each_element([&](int, const auto& v) {
    dofs.element_equations(v.cps, eq);
    for (const int a : eq)
      for (const int b : eq)
        if (a >= 0 && b >= 0) t.emplace_back(a, b, 0.0);
  });
  Eigen::SparseMatrix<double> K(dofs.num_free(), dofs.num_free());
  K.setFromTriplets(t.begin(), t.end());
  K.makeCompressed();
  return K;
}

void add_follower_pressure(const Body& body, const DofMap& dofs, const std::vector<PatchSide>& faces, double p,
                           const Eigen::MatrixXd& u, Eigen::VectorXd& f_ext, Eigen::SparseMatrix<double>* K,
                           const FaceElementFlags* wet) {
  check_shapes(body, dofs, f_ext);
  const int dim = body.space_dim();
  if (u.rows() != body.num_control_points() || u.cols() != dim)
    throw std::invalid_argument(fmt::format("follower pressure: displacement is {} x {}, the body needs {} x {}",
                                            u.rows(), u.cols(), body.num_control_points(), dim));
  if (K) {
    if (K->rows() != dofs.num_free() || K->cols() != dofs.num_free())
      throw std::invalid_argument("follower pressure: the tangent is not free x free");
    if (!K->isCompressed()) K->makeCompressed();
  }
  faces_pressure(body, dofs, faces, p, &u, f_ext, K, nullptr, wet);
}

void add_dead_pressure(const Body& body, const DofMap& dofs, const std::vector<PatchSide>& faces, double p,
                       Eigen::VectorXd& f_ext, const FaceElementFlags* wet) {
  check_shapes(body, dofs, f_ext);
  faces_pressure(body, dofs, faces, p, nullptr, f_ext, nullptr, nullptr, wet);
}

void add_dead_traction(const Body& body, const DofMap& dofs, const std::vector<PatchSide>& faces,
                       const Eigen::VectorXd& traction, Eigen::VectorXd& f_ext) {
  check_shapes(body, dofs, f_ext);
  if (traction.size() != body.space_dim())
    throw std::invalid_argument(fmt::format("traction load: {} components in {}D", traction.size(), body.space_dim()));
  faces_pressure(body, dofs, faces, 0.0, nullptr, f_ext, nullptr, traction.data());
}

}  // namespace igac
