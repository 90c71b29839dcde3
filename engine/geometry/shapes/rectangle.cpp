// SPDX-License-Identifier: BSD-3-Clause
#include "engine/geometry/shapes/shape_support.hpp"

namespace igac {

using namespace shape_support;

Geometry rectangle(double lx, double ly) {
  check_positive(lx, "rectangle width");
  check_positive(ly, "rectangle height");
  Eigen::MatrixXd P(4, 2);
  P << 0, 0, lx, 0, 0, ly, lx, ly;
  Geometry g{NurbsPatch({bezier(1), bezier(1)}, P, Eigen::VectorXd::Ones(4)), {}};
  g.faces["left"] = {Face{0, false}};
  g.faces["right"] = {Face{0, true}};
  g.faces["bottom"] = {Face{1, false}};
  g.faces["top"] = {Face{1, true}};
  return g;
}

namespace {
constexpr ShapeKey kKeys[] = {{"size", "the lengths along x and y", 2}};
}  // namespace

const ShapeType& rectangle_shape() {
  static const ShapeType type{"rectangle", "rectangle [0, Lx] x [0, Ly]", 2, false, kKeys,
                              [](const ShapeValues& v) { return rectangle(v.at("size").at(0), v.at("size").at(1)); }};
  return type;
}

}  // namespace igac
