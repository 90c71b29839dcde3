// Rigid obstacles behind one small interface: at a point x of space an
// obstacle gives the signed normal gap g_n (positive when x is outside it)
// and its own outward unit normal n (DESIGN.md: g_n = (x - x_obstacle) . n).
//  - RigidPlane: through `point`, outward normal `normal`; g_n = (x - x0) . n.
//  - RigidSphere (a circle in 2D, a ball in 3D): g_n = |x - c| - r,
//    n = (x - c) / |x - c|, for a body pressed against its outside.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>

namespace igac {

struct ObstacleProbe {
  double gap = 0;
  Eigen::VectorXd normal;
  // dn/dx, the change of the normal with the point (large deformation
  // linearises the gap with it): zero for a plane, (I - n n^T)/|x - c| for
  // a sphere.  Filled only when asked for.
  Eigen::MatrixXd normal_derivative;
};

class Obstacle {
 public:
  virtual ~Obstacle() = default;
  virtual ObstacleProbe probe(const Eigen::VectorXd& x, bool with_derivative = false) const = 0;
  // For a point on the obstacle's surface, its tangent directions are those
  // orthogonal to the normal there: the "horizontal" distance used for r.
  virtual std::string describe() const = 0;
};

class RigidPlane final : public Obstacle {
 public:
  // Throws std::invalid_argument for a zero normal or mismatched sizes.
  RigidPlane(Eigen::VectorXd point, Eigen::VectorXd normal);
  ObstacleProbe probe(const Eigen::VectorXd& x, bool with_derivative = false) const override;
  std::string describe() const override;

 private:
  Eigen::VectorXd point_, normal_;
};

class RigidSphere final : public Obstacle {
 public:
  RigidSphere(Eigen::VectorXd centre, double radius);
  ObstacleProbe probe(const Eigen::VectorXd& x, bool with_derivative = false) const override;
  std::string describe() const override;

 private:
  Eigen::VectorXd centre_;
  double radius_;
};

}  // namespace igac
