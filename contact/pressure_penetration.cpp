// SPDX-License-Identifier: BSD-3-Clause
#include "contact/pressure_penetration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

namespace igac {

namespace {

// The corners of element e of a face patch (the parameter box's corners
// mapped to the reference configuration), each as integer coordinates on
// a grid of `cell` (so that corners shared by two elements compare equal).
std::vector<std::array<long long, 3>> element_corners(const NurbsPatch& face, const PatchQuadrature& quad, int e,
                                                      double cell, Eigen::VectorXd& centre) {
  const int pd = face.param_dim();
  const std::array<int, 3> index = quad.element_index(e);
  std::array<std::vector<double>, 2> breaks;
  for (int d = 0; d < pd; ++d) breaks[size_t(d)] = face.knots(d).breakpoints();
  std::vector<std::array<long long, 3>> out;
  Eigen::VectorXd xi(pd);
  for (int c = 0; c < (1 << pd); ++c) {
    for (int d = 0; d < pd; ++d) xi[d] = breaks[size_t(d)][size_t(index[size_t(d)] + ((c >> d) & 1))];
    const Eigen::VectorXd X = face.point(xi);
    std::array<long long, 3> key{0, 0, 0};
    for (int i = 0; i < X.size(); ++i) key[size_t(i)] = std::llround(X[i] / cell);
    out.push_back(key);
  }
  for (int d = 0; d < pd; ++d)
    xi[d] = 0.5 * (breaks[size_t(d)][size_t(index[size_t(d)])] + breaks[size_t(d)][size_t(index[size_t(d)] + 1)]);
  centre = face.point(xi);
  return out;
}

}  // namespace

FluidFront::FluidFront(const Body& body, std::vector<PatchSide> faces, const Eigen::VectorXd& entry)
    : faces_(std::move(faces)) {
  if (faces_.empty()) throw std::invalid_argument("a fluid front needs the faces it wets");
  if (entry.size() != body.space_dim())
    throw std::invalid_argument(fmt::format("a fluid entry point of {} coordinates in {}D", entry.size(), body.space_dim()));
  const Eigen::MatrixXd& P = body.points();
  const double cell = 1e-8 * (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
  const int shared_to_meet = body.space_dim() - 1;  // a corner in 2D, an edge (two corners) in 3D
  std::map<std::array<long long, 3>, std::vector<int>> at_corner;
  std::vector<std::vector<std::array<long long, 3>>> corners;
  double nearest = std::numeric_limits<double>::infinity();
  first_.push_back(0);
  Eigen::VectorXd centre;
  for (int s = 0; s < int(faces_.size()); ++s) {
    const NurbsPatch face = body.side_patch(faces_[size_t(s)]);
    const PatchQuadrature quad = body.side_quadrature(faces_[size_t(s)], 1);
    for (int e = 0; e < quad.num_elements(); ++e) {
      const int node = first_.back() + e;
      corners.push_back(element_corners(face, quad, e, cell, centre));
      for (const auto& key : corners.back()) at_corner[key].push_back(node);
      if (const double d = (centre - entry).norm(); d < nearest) {
        nearest = d;
        entry_side_ = s;
        entry_element_ = e;
      }
    }
    first_.push_back(first_.back() + quad.num_elements());
  }
  neighbours_.resize(size_t(first_.back()));
  for (int node = 0; node < first_.back(); ++node) {
    std::map<int, int> shared;  // other node -> corners shared
    for (const auto& key : corners[size_t(node)])
      for (const int other : at_corner[key])
        if (other != node) ++shared[other];
    for (const auto& [other, count] : shared)
      if (count >= shared_to_meet) neighbours_[size_t(node)].push_back(other);
  }
}

FaceElementFlags FluidFront::none() const {
  FaceElementFlags out(faces_.size());
  for (size_t s = 0; s < faces_.size(); ++s) out[s].assign(size_t(first_[s + 1] - first_[s]), 0);
  return out;
}

FaceElementFlags FluidFront::wet(const FaceElementFlags& pressed) const {
  const auto side_of = [&](int node) { return int(std::upper_bound(first_.begin(), first_.end(), node) - first_.begin()) - 1; };
  const auto is_pressed = [&](int node) {
    const int s = side_of(node);
    return pressed[size_t(s)][size_t(node - first_[size_t(s)])] != 0;
  };
  FaceElementFlags out = none();
  const int start = first_[size_t(entry_side_)] + entry_element_;
  if (is_pressed(start)) return out;
  std::vector<int> queue{start};
  out[size_t(entry_side_)][size_t(entry_element_)] = 1;
  while (!queue.empty()) {
    const int node = queue.back();
    queue.pop_back();
    for (const int next : neighbours_[size_t(node)]) {
      const int s = side_of(next);
      char& flag = out[size_t(s)][size_t(next - first_[size_t(s)])];
      if (flag || is_pressed(next)) continue;
      flag = 1;
      queue.push_back(next);
    }
  }
  return out;
}

void mark_pressed(const FluidFront& front, const ContactFace& cf, const Eigen::VectorXd& lambda,
                  FaceElementFlags& pressed) {
  const int points = cf.quadrature_points();
  std::vector<int> K;
  std::vector<double> B;
  Eigen::VectorXd xi;
  for (const ContactSide& side : cf.sides) {
    const auto it = std::find(front.faces().begin(), front.faces().end(), side.side);
    if (it == front.faces().end()) continue;
    std::vector<char>& flags = pressed[size_t(it - front.faces().begin())];
    const PatchQuadrature quad = side.quadrature(points);
    ElementData v;
    for (int e = 0; e < quad.num_elements(); ++e) {
      quad.evaluate(e, v, false);
      double force = 0;  // int_e -lambda_h dGamma_0
      for (int q = 0; q < v.JxW.size(); ++q) {
        xi = v.xi.row(q).transpose();
        side.space.basis(xi, K, B);
        for (size_t k = 0; k < K.size(); ++k) force -= lambda[side.first_multiplier + K[k]] * B[k] * v.JxW[q];
      }
      if (force > 0) flags[size_t(e)] = 1;
    }
  }
}

}  // namespace igac
