// SPDX-License-Identifier: BSD-3-Clause
// Rigid infinite cylinder in 3D (a roller, a pin) pressed on from outside:
// axis through `point` along the unit `axis` a, radius r.  With
// d = (x - p) - ((x - p) . a) a:  g_n = |d| - r,  n = d / |d|,
// dn/dx = (I - a a^T - n n^T) / |d|.
#pragma once

#include "contact/obstacle.hpp"

namespace igac {

class RigidCylinder final : public Obstacle {
 public:
  // Throws std::invalid_argument for a zero axis, a radius <= 0, or a space that is not 3D.
  RigidCylinder(Eigen::VectorXd point, Eigen::VectorXd axis, double radius);
  ObstacleProbe probe(const Eigen::VectorXd& x, bool with_derivative = false) const override;
  std::string describe() const override;

 private:
  Eigen::VectorXd point_, axis_;
  double radius_;
};

const ObstacleType& cylinder_obstacle();

}  // namespace igac
