// SPDX-License-Identifier: BSD-3-Clause
#include "contact/obstacles/cylinder.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <stdexcept>
#include <vector>

#include "engine/numerical_failure.hpp"

namespace igac {

RigidCylinder::RigidCylinder(Eigen::VectorXd point, Eigen::VectorXd axis, double radius)
    : point_(std::move(point)), axis_(std::move(axis)), radius_(radius) {
  if (point_.size() != 3 || axis_.size() != 3) throw std::invalid_argument("a cylinder obstacle lives in 3D");
  const double n = axis_.norm();
  if (!(n > 0)) throw std::invalid_argument("cylinder axis is zero");
  axis_ /= n;
  if (!(radius > 0)) throw std::invalid_argument(fmt::format("obstacle radius {} must be positive", radius));
}

ObstacleProbe RigidCylinder::probe(const Eigen::VectorXd& x, bool with_derivative) const {
  const Eigen::VectorXd rel = x - point_;
  const Eigen::VectorXd d = rel - rel.dot(axis_) * axis_;
  const double r = d.norm();
  if (!(r > 0)) throw NumericalFailure("a point sits on the axis of the rigid cylinder: no normal there");
  ObstacleProbe p{r - radius_, d / r, {}};
  if (with_derivative)
    p.normal_derivative =
        (Eigen::MatrixXd::Identity(3, 3) - axis_ * axis_.transpose() - p.normal * p.normal.transpose()) / r;
  return p;
}

std::string RigidCylinder::describe() const {
  return fmt::format("rigid cylinder of radius {} about the axis through ({}) along ({})", radius_,
                     fmt::join(std::vector<double>(point_.data(), point_.data() + 3), ", "),
                     fmt::join(std::vector<double>(axis_.data(), axis_.data() + 3), ", "));
}

namespace {
constexpr ObstacleKey kCylinderKeys[] = {
    {"point", "a point of the axis"},
    {"axis", "the axis direction", true, false, true},
    {"radius", "the radius", false, true},
};
}  // namespace

const ObstacleType& cylinder_obstacle() {
  static const ObstacleType type{"cylinder", "rigid infinite cylinder (3D), pressed on from outside", kCylinderKeys, 3, 3,
                                 [](const ObstacleValues& v) {
                                   return std::unique_ptr<Obstacle>(std::make_unique<RigidCylinder>(
                                       Eigen::Map<const Eigen::VectorXd>(v.at("point").data(), Eigen::Index(v.at("point").size())), Eigen::Map<const Eigen::VectorXd>(v.at("axis").data(), Eigen::Index(v.at("axis").size())), v.at("radius").at(0)));
                                 }};
  return type;
}

}  // namespace igac
