// SPDX-License-Identifier: BSD-3-Clause
#include "engine/geometry/shapes/shape_support.hpp"

namespace igac {

using namespace shape_support;

Geometry quarter_disc(double R) {
  check_positive(R, "radius");
  const double d = 0.5 * R;  // the straight corner D = (0, -d)
  Eigen::MatrixXd P(9, 2);
  Eigen::VectorXd w = Eigen::VectorXd::Ones(9);
  // row v = 0: the arc (exact circle)
  P.row(0) << 0, -R;
  P.row(1) << R, -R;
  w[1] = kHalfSqrt2;
  P.row(2) << R, 0;
  // row v = 1/2
  P.row(3) << 0, -(R + d) / 2;
  P.row(4) << 0.6 * R, -0.6 * R;  // chosen for the most even det J (min/max)
  P.row(5) << R / 2, 0;
  // row v = 1: x = 0 from D to the centre
  P.row(6) << 0, -d;
  P.row(7) << 0, -d / 2;
  P.row(8) << 0, 0;
  Geometry g{NurbsPatch({bezier(2), bezier(2)}, P, w), {}};
  g.faces["curved"] = {Face{1, false}};
  g.faces["top"] = {Face{0, true}};
  g.faces["left"] = {Face{0, false}, Face{1, true}};
  return g;
}

namespace {
constexpr ShapeKey kKeys[] = {{"radius", "the radius", 1}};
}  // namespace

const ShapeType& quarter_disc_shape() {
  static const ShapeType type{"quarter_disc", "quarter of a disc, the 2D Hertz body", 2, true, kKeys,
                              [](const ShapeValues& v) { return quarter_disc(v.at("radius").at(0)); }};
  return type;
}

}  // namespace igac
