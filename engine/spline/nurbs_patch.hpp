// SPDX-License-Identifier: BSD-3-Clause
// A NURBS patch: a tensor product of univariate B-spline bases with positive
// weights and control points in R^space_dim (Piegl & Tiller ch. 4; paper,
// section 1.2).  The parametric dimension may be lower than the space
// dimension: a face of a 3D patch is a 2D patch in R^3.
//
// Control points are numbered with the first parametric direction fastest:
// i = i0 + n0 * (i1 + n1 * i2).  The patch owns its knots, points and weights;
// refinement (refinement.hpp) returns new patches and never changes geometry.
//
// A revolved patch (2D, in the plane r = x >= 0, z = y) stands for the solid
// it sweeps turning once about the y axis (an axisymmetric model): its
// measures carry the length 2 pi r of the circle a point sweeps
// (ring_length), so integrals over it and over its faces (which inherit the
// flag) are over the whole solid of revolution.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <numbers>
#include <vector>

#include "engine/spline/knot_vector.hpp"

namespace igac {

// A face of the parametric cube: direction `direction` held at its first
// (`at_end == false`) or last knot.
struct Face {
  int direction = 0;
  bool at_end = false;
  bool operator==(const Face& o) const { return direction == o.direction && at_end == o.at_end; }
};

class NurbsPatch {
 public:
  NurbsPatch() = default;
  // Throws SplineError when the data do not fit together or a weight is not
  // positive and finite.
  NurbsPatch(std::vector<KnotVector> knots, Eigen::MatrixXd points, Eigen::VectorXd weights);

  int param_dim() const { return int(knots_.size()); }
  int space_dim() const { return int(points_.cols()); }
  const KnotVector& knots(int d) const { return knots_[d]; }
  const std::vector<KnotVector>& all_knots() const { return knots_; }
  int degree(int d) const { return knots_[d].degree(); }
  int num_basis(int d) const { return knots_[d].num_basis(); }
  int num_control_points() const { return int(points_.rows()); }
  int num_elements() const;
  const Eigen::MatrixXd& points() const { return points_; }
  const Eigen::VectorXd& weights() const { return weights_; }

  // Global control point index of a multi-index (unused trailing entries 0).
  int index(const std::array<int, 3>& i) const {
    return i[0] + num_basis(0) * (param_dim() > 1 ? i[1] + num_basis(1) * (param_dim() > 2 ? i[2] : 0) : 0);
  }
  std::array<int, 3> multi_index(int i) const;

  // Physical point at parametric coordinates xi.
  Eigen::VectorXd point(const Eigen::VectorXd& xi) const;
  // Jacobian dX/dxi (space_dim x param_dim) at xi.
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& xi) const;
  // Second parametric derivatives of the point at xi: space_dim x (pd * pd),
  // column a * pd + b = d^2 X / dxi_a dxi_b (the curvature of a face, e.g.
  // for the large-deformation mortar contact's linearisation), from the
  // homogeneous form X = A / W: X,ab = (A,ab - W,ab X - W,a X,b - W,b X,a) / W.
  Eigen::MatrixXd second_derivatives(const Eigen::VectorXd& xi) const;
  // Rational basis values and first parametric derivatives at xi:
  // indices of the nonzero functions, values, derivatives (n x param_dim).
  void rational_basis(const Eigen::VectorXd& xi, std::vector<int>& indices,
                      Eigen::VectorXd& values, Eigen::MatrixXd& derivs) const;
  // A field given by coefficients (one row per control point) at xi, and its
  // parametric gradient (field_dim x param_dim).
  Eigen::VectorXd field(const Eigen::MatrixXd& coefs, const Eigen::VectorXd& xi,
                        Eigen::MatrixXd* dfield_dxi = nullptr) const;

  // Control point indices lying on a face, in the face's own numbering.
  std::vector<int> face_control_points(const Face& f) const;
  // The face as a patch of one parametric dimension less (revolved if this is).
  NurbsPatch face_patch(const Face& f) const;

  // The axisymmetric model (see the head of this file).  Throws SplineError
  // unless the patch lies in 2D with every control point at x >= 0 (to 1e-10 of its size).
  void set_revolved(bool revolved);
  bool revolved() const { return revolved_; }
  // The factor a measure at point X carries: 2 pi X_0 when revolved, else 1.
  template <class Point>
  double ring_length(const Point& X) const {
    return revolved_ ? 2 * std::numbers::pi * X[0] : 1.0;
  }

 private:
  std::vector<KnotVector> knots_;
  Eigen::MatrixXd points_;
  Eigen::VectorXd weights_;
  bool revolved_ = false;
};

// Outward area vector n dA/dxi_face at a point of a face, from the face
// tangents (columns of the face patch's Jacobian): s * cof(J) e_d.
Eigen::VectorXd face_area_vector(const Face& f, const Eigen::MatrixXd& face_jacobian);

}  // namespace igac
