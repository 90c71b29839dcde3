// SPDX-License-Identifier: BSD-3-Clause
// Rigid obstacles behind one small interface: at a point x of space an
// obstacle gives the signed normal gap g_n (positive when x is outside it)
// and its own outward unit normal n (docs/design.md, "Gap and sign convention": g_n = (x - x_obstacle) . n).
// The types (contact/obstacles/): plane, sphere (a circle in 2D), cylinder
// (3D, infinite), edge (two faces meeting at a rounded edge).
#pragma once

#include <Eigen/Dense>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>
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
  // An obstacle with an edge (contact/obstacles/edge.hpp): how far the
  // point x lies past the edge (the extrusion into a gap there; 0 for a
  // point that is not past it); none for obstacles without an edge.
  virtual std::optional<double> reach_past_edge(const Eigen::VectorXd& /*x*/) const { return std::nullopt; }
};

// The obstacle moved rigidly by `shift`: g(x) = g_base(x - shift).  A moving
// obstacle is its reference position translated by t * motion.
class TranslatedObstacle final : public Obstacle {
 public:
  // Borrows `base` (which must outlive this) ...
  TranslatedObstacle(const Obstacle& base, Eigen::VectorXd shift) : base_(&base), shift_(std::move(shift)) {}
  // ... or owns it.
  TranslatedObstacle(std::unique_ptr<Obstacle> base, Eigen::VectorXd shift)
      : owned_(std::move(base)), base_(owned_.get()), shift_(std::move(shift)) {}
  ObstacleProbe probe(const Eigen::VectorXd& x, bool with_derivative = false) const override {
    return base_->probe(x - shift_, with_derivative);
  }
  std::optional<double> reach_past_edge(const Eigen::VectorXd& x) const override {
    return base_->reach_past_edge(x - shift_);
  }
  std::string describe() const override;

 private:
  std::unique_ptr<Obstacle> owned_;
  const Obstacle* base_;
  Eigen::VectorXd shift_;
};

// The obstacle types a case file can name, one file each under
// contact/obstacles/ (listed in contact/CMakeLists.txt) and one line in
// kObstacleTypes (contact/obstacle.cpp).  A type
// declares its keys; the case file checks them (presence, length, sign) with
// one-line errors and hands the values to `make`.
using ObstacleValues = std::map<std::string, std::vector<double>, std::less<>>;
struct ObstacleKey {
  std::string_view key, meaning;
  bool vector = true;     // a point or direction of the space's dimension; else one number
  bool positive = false;  // a number that must be > 0
  bool nonzero = false;   // a direction that must not be zero
};
struct ObstacleType {
  std::string_view name, description;
  std::span<const ObstacleKey> keys;
  int min_dim = 2, max_dim = 3;
  // Throws std::invalid_argument for values the keys' checks cannot see.
  std::unique_ptr<Obstacle> (*make)(const ObstacleValues& values);
};
std::span<const ObstacleType* const> obstacle_types();
const ObstacleType* find_obstacle_type(std::string_view name);

}  // namespace igac

#include "contact/obstacles/cylinder.hpp"
#include "contact/obstacles/edge.hpp"
#include "contact/obstacles/plane.hpp"
#include "contact/obstacles/sphere.hpp"
