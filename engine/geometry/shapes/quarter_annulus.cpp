// SPDX-License-Identifier: BSD-3-Clause
#include "engine/geometry/shapes/shape_support.hpp"

namespace igac {

using namespace shape_support;

Geometry quarter_annulus(double a, double b) {
  check_positive(a, "inner radius");
  check_positive(b, "outer radius");
  if (!(b > a)) throw SplineError(fmt::format("outer radius {} must exceed inner radius {}", b, a));
  // u radial (degree 1), v along the angle from the x axis (degree 2): det J > 0.
  Eigen::MatrixXd P(6, 2);
  Eigen::VectorXd w(6);
  P << a, 0, b, 0, a, a, b, b, 0, a, 0, b;
  w << 1, 1, kHalfSqrt2, kHalfSqrt2, 1, 1;
  Geometry g{NurbsPatch({bezier(1), bezier(2)}, P, w), {}};
  g.faces["inner"] = {Face{0, false}};
  g.faces["outer"] = {Face{0, true}};
  g.faces["bottom"] = {Face{1, false}};
  g.faces["left"] = {Face{1, true}};
  return g;
}

namespace {
constexpr ShapeKey kKeys[] = {{"inner_radius", "the inner radius", 1}, {"outer_radius", "the outer radius (above the inner one)", 1}};
}  // namespace

const ShapeType& quarter_annulus_shape() {
  static const ShapeType type{"quarter_annulus", "quarter of an annulus (thick cylinder)", 2, true, kKeys,
                              [](const ShapeValues& v) { return quarter_annulus(v.at("inner_radius").at(0), v.at("outer_radius").at(0)); }};
  return type;
}

}  // namespace igac
