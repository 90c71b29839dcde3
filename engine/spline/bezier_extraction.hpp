// SPDX-License-Identifier: BSD-3-Clause
// Bezier extraction: every element of a NURBS patch written as a rational
// Bezier element (Borden, Scott, Evans & Hughes 2011, "Isogeometric finite
// element data structures based on Bezier extraction of NURBS"; Piegl &
// Tiller 5.3, "decomposition into Bezier pieces").
//
// How: every interior breakpoint of every direction is raised by knot
// insertion (refinement.hpp, on the homogeneous coefficients w P, w, w u) to
// multiplicity at least p.  On a span bounded by knots of multiplicity >= p
// the p+1 B-splines that do not vanish are the Bernstein polynomials of the
// span, so the span's control points, weights and field coefficients are its
// rational Bezier representation:
//     X(s) = sum_i w_i B_i(s) X_i / sum_i w_i B_i(s),   s in [0, 1]^d,
// and a field u carried with the patch (u(xi) = sum_A R_A(xi) u_A) becomes
// u(s) = sum_i w_i B_i(s) u_i / sum_i w_i B_i(s) on the same element.  Knot
// insertion is exact, so both agree with the patch at xi = a + s (b - a) to
// round-off.  Each element owns its (p+1)^d points: shared boundary points are
// repeated, which is what discontinuous per-element data need.
//
// Local points are numbered lexicographically, first direction fastest:
// i = i0 + (p0+1) (i1 + (p1+1) i2).  io/vtk_output.cpp maps them to VTK's
// Bezier cell ordering.
#pragma once

#include <array>
#include <vector>

#include "engine/spline/nurbs_patch.hpp"

namespace igac {

// Bernstein polynomials of degree p on [0, 1] at s and their derivatives.
void bernstein(int p, double s, double* values, double* derivs);

struct BezierElement {
  std::array<int, 3> index{0, 0, 0};      // element multi-index in the patch
  std::array<double, 3> lower{0, 0, 0};   // parametric box [lower, upper] in the patch
  std::array<double, 3> upper{1, 1, 1};
  Eigen::MatrixXd points;                 // n_local x space_dim
  Eigen::VectorXd weights;                // n_local
  std::vector<Eigen::MatrixXd> fields;    // each n_local x field_dim

  // Patch parameter of local coordinates s in [0, 1]^param_dim.
  Eigen::VectorXd parameter(const Eigen::VectorXd& s) const;
};

class BezierMesh {
 public:
  BezierMesh() = default;
  // Extracts every element of `patch`; `fields` (one row per control point)
  // are carried along.  Throws SplineError when a field has the wrong size.
  explicit BezierMesh(const NurbsPatch& patch, const std::vector<Eigen::MatrixXd>& fields = {});

  // Adds the elements of `other` after this mesh's (the patches of a
  // multi-patch body as one mesh).  Throws SplineError unless both have the
  // same dimensions and degrees.
  void append(const BezierMesh& other);

  int param_dim() const { return param_dim_; }
  int space_dim() const { return space_dim_; }
  // Degree of direction d (0 for d >= param_dim).
  int degree(int d) const { return degree_[d]; }
  const std::array<int, 3>& degrees() const { return degree_; }
  int num_local() const { return num_local_; }
  int num_elements() const { return int(elements_.size()); }
  int num_points() const { return num_elements() * num_local_; }
  const std::vector<BezierElement>& elements() const { return elements_; }
  const BezierElement& element(int e) const { return elements_[e]; }
  // Local point number of the multi-index (i0, i1, i2).
  int local_index(int i0, int i1, int i2) const {
    return i0 + (degree_[0] + 1) * (i1 + (degree_[1] + 1) * i2);
  }

  // Rational Bezier basis of the element at s: values R (n_local) and
  // derivatives dR/ds (n_local x param_dim).  Workspace-free, allocates.
  void basis(const BezierElement& el, const Eigen::VectorXd& s, Eigen::VectorXd& R, Eigen::MatrixXd* dR = nullptr) const;
  // Geometry and carried fields of an element at s.
  Eigen::VectorXd point(int e, const Eigen::VectorXd& s) const;
  Eigen::VectorXd field(int e, int f, const Eigen::VectorXd& s) const;

 private:
  int param_dim_ = 0, space_dim_ = 0, num_local_ = 1;
  std::array<int, 3> degree_{0, 0, 0};
  std::vector<BezierElement> elements_;
};

}  // namespace igac
