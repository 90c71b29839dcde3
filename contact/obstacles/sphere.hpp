// SPDX-License-Identifier: BSD-3-Clause
// Rigid sphere (a circle in 2D) pressed on from outside: g_n = |x - c| - r,
// n = (x - c) / |x - c|, dn/dx = (I - n n^T) / |x - c|.
#pragma once

#include "contact/obstacle.hpp"

namespace igac {

class RigidSphere final : public Obstacle {
 public:
  RigidSphere(Eigen::VectorXd centre, double radius);
  ObstacleProbe probe(const Eigen::VectorXd& x, bool with_derivative = false) const override;
  std::string describe() const override;

 private:
  Eigen::VectorXd centre_;
  double radius_;
};

const ObstacleType& sphere_obstacle();

}  // namespace igac
