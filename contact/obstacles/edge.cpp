// SPDX-License-Identifier: BSD-3-Clause
#include "contact/obstacles/edge.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <stdexcept>
#include <vector>

#include "engine/numerical_failure.hpp"

namespace igac {

namespace {

Eigen::VectorXd unit(Eigen::VectorXd v, const char* what) {
  const double n = v.norm();
  if (!(n > 0)) throw std::invalid_argument(fmt::format("edge {} is zero", what));
  return v / n;
}

std::string listed(const Eigen::VectorXd& v) {
  return fmt::format("{}", fmt::join(std::vector<double>(v.data(), v.data() + v.size()), ", "));
}

}  // namespace

RigidEdge::RigidEdge(Eigen::VectorXd corner, Eigen::VectorXd normal, Eigen::VectorXd second_normal, double radius)
    : corner_(std::move(corner)), n1_(unit(std::move(normal), "normal")), n2_(unit(std::move(second_normal), "second_normal")),
      radius_(radius) {
  const Eigen::Index dim = corner_.size();
  if ((dim != 2 && dim != 3) || n1_.size() != dim || n2_.size() != dim)
    throw std::invalid_argument("an edge obstacle lives in 2D or 3D, its corner and normals of one dimension");
  const double c = n1_.dot(n2_);
  if (std::abs(c) > 1 - 1e-9)
    throw std::invalid_argument("the edge's two normals are parallel: its faces must meet at an angle");
  if (!(radius > 0)) throw std::invalid_argument(fmt::format("edge radius {} must be positive", radius));
  apex_ = corner_ - radius_ * (n1_ + n2_) / (1 + c);
  if (dim == 3) edge_ = Eigen::Vector3d(n1_[0], n1_[1], n1_[2]).cross(Eigen::Vector3d(n2_[0], n2_[1], n2_[2])).normalized();
}

ObstacleProbe RigidEdge::probe(const Eigen::VectorXd& x, bool with_derivative) const {
  const Eigen::Index dim = x.size();
  const double c = n1_.dot(n2_);
  const double a1 = (x - apex_).dot(n1_), a2 = (x - apex_).dot(n2_);
  ObstacleProbe p;
  const auto flat = [&](double a, const Eigen::VectorXd& n) {
    p.gap = a - radius_;
    p.normal = n;
    if (with_derivative) p.normal_derivative = Eigen::MatrixXd::Zero(dim, dim);
  };
  if (a1 <= 0 && a2 <= 0) {  // inside the shrunk wedge: the nearer face
    a1 >= a2 ? flat(a1, n1_) : flat(a2, n2_);
  } else if (a1 > 0 && a2 - a1 * c <= 0) {
    flat(a1, n1_);
  } else if (a2 > 0 && a1 - a2 * c <= 0) {
    flat(a2, n2_);
  } else {  // nearest to the apex line
    Eigen::VectorXd d = x - apex_;
    if (dim == 3) d -= d.dot(edge_) * edge_;
    const double r = d.norm();
    if (!(r > 0)) throw NumericalFailure("a point sits on the rounded edge's axis: no normal there");
    p.gap = r - radius_;
    p.normal = d / r;
    if (with_derivative) {
      p.normal_derivative = Eigen::MatrixXd::Identity(dim, dim) - p.normal * p.normal.transpose();
      if (dim == 3) p.normal_derivative -= edge_ * edge_.transpose();
      p.normal_derivative /= r;
    }
  }
  return p;
}

std::optional<double> RigidEdge::reach_past_edge(const Eigen::VectorXd& x) const {
  if ((x - corner_).dot(n2_) <= 0) return 0.0;
  return std::max(0.0, -(x - corner_).dot(n1_));
}

std::string RigidEdge::describe() const {
  return fmt::format("rigid edge at ({}) between faces with normals ({}) and ({}), rounded with radius {}",
                     listed(corner_), listed(n1_), listed(n2_), radius_);
}

namespace {
constexpr ObstacleKey kEdgeKeys[] = {
    {"point", "the corner where the two faces meet (before rounding)"},
    {"normal", "the outward normal of the face the body bears on (a gland's wall)", true, false, true},
    {"second_normal", "the outward normal of the other face, past which the body may extrude", true, false, true},
    {"radius", "the rounding of the edge", false, true},
};

Eigen::VectorXd vector_of(const ObstacleValues& v, const char* key) {
  return Eigen::Map<const Eigen::VectorXd>(v.at(key).data(), Eigen::Index(v.at(key).size()));
}
}  // namespace

const ObstacleType& edge_obstacle() {
  static const ObstacleType type{
      "edge", "rigid convex edge, two faces meeting at a rounded corner (2D or 3D)", kEdgeKeys, 2, 3,
      [](const ObstacleValues& v) {
        return std::unique_ptr<Obstacle>(std::make_unique<RigidEdge>(
            vector_of(v, "point"), vector_of(v, "normal"), vector_of(v, "second_normal"), v.at("radius").at(0)));
      }};
  return type;
}

}  // namespace igac
