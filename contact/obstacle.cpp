#include "contact/obstacle.hpp"

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

RigidSphere::RigidSphere(Eigen::VectorXd centre, double radius) : centre_(std::move(centre)), radius_(radius) {
  if (!(radius > 0)) throw std::invalid_argument(fmt::format("obstacle radius {} must be positive", radius));
}

ObstacleProbe RigidSphere::probe(const Eigen::VectorXd& x, bool with_derivative) const {
  const Eigen::VectorXd d = x - centre_;
  const double r = d.norm();
  if (!(r > 0)) throw std::runtime_error("a point sits at the centre of the rigid sphere: no normal there");
  ObstacleProbe p{r - radius_, d / r, {}};
  if (with_derivative)
    p.normal_derivative = (Eigen::MatrixXd::Identity(x.size(), x.size()) - p.normal * p.normal.transpose()) / r;
  return p;
}

std::string RigidSphere::describe() const {
  return fmt::format("rigid {} of radius {} centred at ({})", centre_.size() == 2 ? "circle" : "sphere", radius_,
                     fmt::join(std::vector<double>(centre_.data(), centre_.data() + centre_.size()), ", "));
}

}  // namespace igac
