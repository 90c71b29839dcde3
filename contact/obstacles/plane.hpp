// SPDX-License-Identifier: BSD-3-Clause
// Rigid plane through `point` with outward unit normal `normal`:
// g_n = (x - point) . n, dn/dx = 0.
#pragma once

#include "contact/obstacle.hpp"

namespace igac {

class RigidPlane final : public Obstacle {
 public:
  // Throws std::invalid_argument for a zero normal or mismatched sizes.
  RigidPlane(Eigen::VectorXd point, Eigen::VectorXd normal);
  ObstacleProbe probe(const Eigen::VectorXd& x, bool with_derivative = false) const override;
  std::string describe() const override;

 private:
  Eigen::VectorXd point_, normal_;
};

const ObstacleType& plane_obstacle();

}  // namespace igac
