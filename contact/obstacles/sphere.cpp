// SPDX-License-Identifier: BSD-3-Clause
#include "contact/obstacles/sphere.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <stdexcept>
#include <vector>

#include "engine/numerical_failure.hpp"

namespace igac {

RigidSphere::RigidSphere(Eigen::VectorXd centre, double radius) : centre_(std::move(centre)), radius_(radius) {
  if (!(radius > 0)) throw std::invalid_argument(fmt::format("obstacle radius {} must be positive", radius));
}

ObstacleProbe RigidSphere::probe(const Eigen::VectorXd& x, bool with_derivative) const {
  const Eigen::VectorXd d = x - centre_;
  const double r = d.norm();
  if (!(r > 0)) throw NumericalFailure("a point sits at the centre of the rigid sphere: no normal there");
  ObstacleProbe p{r - radius_, d / r, {}};
  if (with_derivative)
    p.normal_derivative = (Eigen::MatrixXd::Identity(x.size(), x.size()) - p.normal * p.normal.transpose()) / r;
  return p;
}

std::string RigidSphere::describe() const {
  return fmt::format("rigid {} of radius {} centred at ({})", centre_.size() == 2 ? "circle" : "sphere", radius_,
                     fmt::join(std::vector<double>(centre_.data(), centre_.data() + centre_.size()), ", "));
}

namespace {
constexpr ObstacleKey kSphereKeys[] = {
    {"centre", "the centre"},
    {"radius", "the radius", false, true},
};
}  // namespace

const ObstacleType& sphere_obstacle() {
  static const ObstacleType type{"sphere", "rigid ball (a disc in 2D), pressed on from outside", kSphereKeys, 2, 3,
                                 [](const ObstacleValues& v) {
                                   return std::unique_ptr<Obstacle>(
                                       std::make_unique<RigidSphere>(Eigen::Map<const Eigen::VectorXd>(v.at("centre").data(), Eigen::Index(v.at("centre").size())), v.at("radius").at(0)));
                                 }};
  return type;
}

}  // namespace igac
