// SPDX-License-Identifier: BSD-3-Clause
#include "contact/obstacles/plane.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <stdexcept>
#include <vector>

namespace igac {

RigidPlane::RigidPlane(Eigen::VectorXd point, Eigen::VectorXd normal) : point_(std::move(point)), normal_(std::move(normal)) {
  if (point_.size() != normal_.size()) throw std::invalid_argument("plane point and normal differ in dimension");
  const double n = normal_.norm();
  if (!(n > 0)) throw std::invalid_argument("plane normal is zero");
  normal_ /= n;
}

ObstacleProbe RigidPlane::probe(const Eigen::VectorXd& x, bool with_derivative) const {
  ObstacleProbe p{(x - point_).dot(normal_), normal_, {}};
  if (with_derivative) p.normal_derivative = Eigen::MatrixXd::Zero(x.size(), x.size());
  return p;
}

std::string RigidPlane::describe() const {
  return fmt::format("rigid plane through ({}) with normal ({})",
                     fmt::join(std::vector<double>(point_.data(), point_.data() + point_.size()), ", "),
                     fmt::join(std::vector<double>(normal_.data(), normal_.data() + normal_.size()), ", "));
}

namespace {
constexpr ObstacleKey kPlaneKeys[] = {
    {"point", "a point of the plane"},
    {"normal", "the plane's outward normal, pointing into the body", true, false, true},
};
}  // namespace

const ObstacleType& plane_obstacle() {
  static const ObstacleType type{"plane", "rigid half-space", kPlaneKeys, 2, 3, [](const ObstacleValues& v) {
    return std::unique_ptr<Obstacle>(std::make_unique<RigidPlane>(Eigen::Map<const Eigen::VectorXd>(v.at("point").data(), Eigen::Index(v.at("point").size())), Eigen::Map<const Eigen::VectorXd>(v.at("normal").data(), Eigen::Index(v.at("normal").size()))));
  }};
  return type;
}

}  // namespace igac
