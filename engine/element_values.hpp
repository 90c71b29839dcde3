// SPDX-License-Identifier: BSD-3-Clause
// Element values with the dimensions known at compile time: per element of a
// patch (pd = sd, a volume) or of a face of it (pd = sd - 1), at its Gauss
// points, the rational basis R_a, its parametric derivatives dR_a/dxi, its
// physical gradient dR_a/dX (volumes, when asked), the point X, the weights
// and, on faces, the outward unit normal (the FEValues role).
//
// ElementValues is the one element-values object of the engine: the linear
// and the total-Lagrangian assembly, the pressure loads and the face loop of
// engine/ and contact/ (face_quadrature.hpp: the weighted gaps, the
// large-deformation contact) read it, and
// PatchQuadrature::evaluate (discretisation.cpp) is the one kernel that
// fills it.  ElementData (discretisation.hpp) is the same values in
// run-time-sized matrices for callers that do not know the dimension (error
// norms, stress recovery, reports): PatchQuadrature fills it from an
// ElementValues.
//
// Nothing allocates once an ElementValues has its size (every element of a
// patch has the same), and 2D works with 2x2 matrices.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "engine/spline/nurbs_patch.hpp"

namespace igac {

template <int pd, int sd>
struct ElementValues {
  static_assert(pd == sd || pd == sd - 1, "a volume element or a face element");
  static constexpr int param_dim = pd, space_dim = sd;
  static constexpr bool is_face = pd < sd;
  using Point = Eigen::Matrix<double, sd, 1>;
  using Param = Eigen::Matrix<double, pd, 1>;

  int n_loc = 0, n_q = 0;
  std::vector<int> cps;        // control points (parent/body numbering)
  std::vector<Point> X_cp;     // their reference positions
  std::vector<double> w_cp;    // and NURBS weights
  std::vector<double> R;       // [q * n_loc + a]
  std::vector<double> dR_dxi;  // [(q * n_loc + a) * pd + d]
  std::vector<double> dR_dX;   // [(q * n_loc + a) * sd + J] (volumes, gradients asked)
  std::vector<Point> X;        // per point
  std::vector<Param> xi;       // per point (parameters of the patch)
  std::vector<double> w;       // per point: Gauss weight times element size (parametric)
  std::vector<double> JxW;     // per point: det J w (volume), |n dA| w (face), times 2 pi r if revolved
  std::vector<Point> normal;   // per point, unit outward (faces)
  double min_det_J = 0;        // volumes: smallest det J at the points
  // The patch is revolved (axisymmetric, engine/spline/nurbs_patch.hpp): JxW
  // carries 2 pi r, and the kinematics add the hoop strain u_r / r.
  bool revolved = false;

  double N(int q, int a) const { return R[size_t(q) * n_loc + a]; }
  // The hoop strain's function of a at point q: R_a / r (axisymmetric).
  double hoop(int q, int a) const { return N(q, a) / X[q][0]; }
  // dR_a/dX at point q: [a * sd + J]
  const double* gradients(int q) const { return dR_dX.data() + size_t(q) * n_loc * sd; }
  // dR_a/dxi at point q: [a * pd + d]
  const double* parametric_derivatives(int q) const { return dR_dxi.data() + size_t(q) * n_loc * pd; }
  // The current position X + u(X) at point q, u given per body control point
  // (one row each): the terms R_a u_a are added to X one by one.
  template <class Field>
  Point displaced(int q, const Field& u) const {
    Point x = X[q];
    for (int a = 0; a < n_loc; ++a) x += N(q, a) * u.row(cps[a]).transpose();
    return x;
  }
};

// The outward area vector n dA/dxi of a face from its tangents T (columns:
// dX/dxi along the face's own directions, in their parametric order):
//   2D: sigma (t_0[1], -t_0[0]),   3D: sigma t_0 x t_1,
// sigma the orientation of the face (face_orientation).  The same vector as
// face_area_vector (nurbs_patch.hpp) with sizes known.
inline double face_orientation(const Face& f, int dim) {
  const double s = f.at_end ? 1.0 : -1.0;
  if (dim == 2) return f.direction == 0 ? s : -s;
  return f.direction == 1 ? -s : s;
}

template <int dim>
Eigen::Matrix<double, dim, 1> oriented_area(double sigma, const Eigen::Matrix<double, dim, dim - 1>& T) {
  if constexpr (dim == 2)
    return sigma * Eigen::Vector2d(T(1, 0), -T(0, 0));
  else
    return sigma * T.col(0).cross(T.col(1));
}

}  // namespace igac
