// SPDX-License-Identifier: BSD-3-Clause
// The multiplier space Lambda_h = S^{p-2} on the contact face (paper, eq. (7)):
// B-splines of degree p-2 on the face's breakpoints, ends repeated p-1 times
// (open), interior breakpoints with the displacement's multiplicities up to
// p-1.  For p = 2: one constant per face element (N2/S0); p = 3:
// continuous piecewise linears (N3/S1).  A breakpoint where the displacement
// is only C0 (multiplicity p: a circle or a ring of one patch at its quarter
// points) keeps multiplicity p-1, where the multipliers of degree p-2 are
// discontinuous: the space two patches meeting there have (ContactFace, one
// space per side; Brivadis, Buffa, Wohlmuth & Wunderlich 2015 take the
// multipliers per patch).  In 3D the face space is the tensor product.
// Multiplier K is numbered first face direction fastest.
#pragma once

#include <vector>

#include "engine/spline/nurbs_patch.hpp"

namespace igac {

class MultiplierSpace {
 public:
  // `face` is the contact face as a patch (param_dim = space_dim - 1).
  // Throws SplineError when p < 2.
  explicit MultiplierSpace(const NurbsPatch& face);

  int size() const { return size_; }
  int degree() const { return knots_[0].degree(); }
  const std::vector<KnotVector>& knots() const { return knots_; }
  // Nonzero multiplier basis functions at face parameter xi.
  void basis(const Eigen::VectorXd& xi, std::vector<int>& indices, std::vector<double>& values) const;
  // Parametric anchor of multiplier K (Greville abscissae), for plots.
  Eigen::VectorXd anchor(int K) const;

 private:
  std::vector<KnotVector> knots_;
  int size_ = 1;
};

}  // namespace igac
