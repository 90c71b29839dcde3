// SPDX-License-Identifier: BSD-3-Clause
// A rigid convex edge with a rounded tip: the body {x : (x - c) . n1 <= 0
// and (x - c) . n2 <= 0} (two faces meeting at the corner c with outward
// unit normals n1, n2; in 3D an infinite straight edge along n1 x n2),
// its edge rounded with radius r: the points within r of the wedge shrunk
// by r.  The end of a gland's wall where an extrusion gap opens, a die's
// shoulder, a step.
//
// With the shrunk wedge's apex c_s = c - r (n1 + n2) / (1 + n1 . n2) and
// a_i = (x - c_s) . n_i:
//  - a point whose nearest point of the shrunk wedge lies on face i
//    (a_i > 0 and a_j - a_i (n1 . n2) <= 0) has g_n = a_i - r, n = n_i and
//    dn/dx = 0;
//  - a point nearest to the apex has, with d its distance vector from the
//    apex line (the edge's direction e removed), g_n = |d| - r, n = d / |d|,
//    dn/dx = (I - e e^T - n n^T) / |d| (a cylinder's);
//  - a point inside the shrunk wedge has g_n = max(a_1, a_2) - r and that
//    face's normal.
// The normal is continuous (r > 0): a face's normal is the apex's where
// the regions meet.
//
// The reach past the edge: how far a point of the body has gone beyond the
// first face, over the second (the extrusion into a gap between the
// second face and what closes it): (x - c) . (-n1) for a point with
// (x - c) . n2 > 0 when positive, else 0.
#pragma once

#include "contact/obstacle.hpp"

namespace igac {

class RigidEdge final : public Obstacle {
 public:
  // Throws std::invalid_argument for a zero normal, normals (anti)parallel,
  // a radius <= 0, or a space that is not 2D or 3D.
  RigidEdge(Eigen::VectorXd corner, Eigen::VectorXd normal, Eigen::VectorXd second_normal, double radius);
  ObstacleProbe probe(const Eigen::VectorXd& x, bool with_derivative = false) const override;
  std::optional<double> reach_past_edge(const Eigen::VectorXd& x) const override;
  std::string describe() const override;

 private:
  Eigen::VectorXd corner_, n1_, n2_, apex_, edge_;  // edge_: the edge's direction (3D), empty in 2D
  double radius_;
};

const ObstacleType& edge_obstacle();

}  // namespace igac
