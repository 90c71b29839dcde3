// SPDX-License-Identifier: BSD-3-Clause
#include "engine/geometry/shapes/shape_support.hpp"

namespace igac {

using namespace shape_support;

Geometry box(double lx, double ly, double lz) {
  check_positive(lx, "box length x");
  check_positive(ly, "box length y");
  check_positive(lz, "box length z");
  Eigen::MatrixXd P(8, 3);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) P.row(i + 2 * j + 4 * k) << i * lx, j * ly, k * lz;
  Geometry g{NurbsPatch({bezier(1), bezier(1), bezier(1)}, P, Eigen::VectorXd::Ones(8)), {}};
  g.faces["left"] = {Face{0, false}};
  g.faces["right"] = {Face{0, true}};
  g.faces["front"] = {Face{1, false}};
  g.faces["back"] = {Face{1, true}};
  g.faces["bottom"] = {Face{2, false}};
  g.faces["top"] = {Face{2, true}};
  return g;
}

namespace {
constexpr ShapeKey kKeys[] = {{"size", "the lengths along x, y and z", 3}};
}  // namespace

const ShapeType& box_shape() {
  static const ShapeType type{"box", "box [0, Lx] x [0, Ly] x [0, Lz]", 3, false, kKeys,
                              [](const ShapeValues& v) { return box(v.at("size").at(0), v.at("size").at(1), v.at("size").at(2)); }};
  return type;
}

}  // namespace igac
