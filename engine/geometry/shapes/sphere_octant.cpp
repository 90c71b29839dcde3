// SPDX-License-Identifier: BSD-3-Clause
#include "engine/geometry/shapes/shape_support.hpp"

namespace igac {

using namespace shape_support;

Geometry sphere_octant(double R) {
  // Revolve the quarter disc, placed in the plane y = 0 as (x, 0, z) with
  // z = its y, about the x axis by 90 degrees (Piegl & Tiller 8.5): the
  // rotation is the third parametric direction, run from the plane z = 0
  // (w = 0) to the plane y = 0 (w = 1) so that det J > 0.
  const Geometry disc = quarter_disc(R);
  const NurbsPatch& d = disc.patch;
  const int n = d.num_control_points();
  Eigen::MatrixXd P(3 * n, 3);
  Eigen::VectorXd w(3 * n);
  const double ring_weight[3] = {1.0, kHalfSqrt2, 1.0};
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < n; ++a) {
      const double x = d.points()(a, 0), z = d.points()(a, 1);  // z <= 0
      // k = 0: (x, -z, 0); k = 1: (x, -z, z) (corner of the control square); k = 2: (x, 0, z)
      const Eigen::Vector3d q = k == 0 ? Eigen::Vector3d(x, -z, 0) : k == 1 ? Eigen::Vector3d(x, -z, z) : Eigen::Vector3d(x, 0, z);
      P.row(k * n + a) = q.transpose();
      w[k * n + a] = d.weights()[a] * ring_weight[k];
    }
  Geometry g{NurbsPatch({d.knots(0), d.knots(1), bezier(2)}, P, w), {}};
  g.faces["curved"] = {Face{1, false}};
  g.faces["top"] = {Face{2, false}};                 // z = 0
  g.faces["back"] = {Face{2, true}};                 // y = 0
  g.faces["left"] = {Face{0, false}, Face{1, true}}; // x = 0
  g.faces["axis"] = {Face{0, true}};                 // collapsed onto the x axis
  return g;
}

namespace {
constexpr ShapeKey kKeys[] = {{"radius", "the radius", 1}};
}  // namespace

const ShapeType& sphere_octant_shape() {
  static const ShapeType type{"sphere_octant", "octant of a ball, the 3D Hertz body", 3, true, kKeys,
                              [](const ShapeValues& v) { return sphere_octant(v.at("radius").at(0)); }};
  return type;
}

}  // namespace igac
