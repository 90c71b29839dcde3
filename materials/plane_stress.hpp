// SPDX-License-Identifier: BSD-3-Clause
// Plane stress: a 2D law whose out-of-plane stress is zero, made from any 3D
// law (a thin plate loaded in its plane).  Forces are per unit reference
// thickness, as in plane strain.
//
// Mathematics.  At an in-plane gradient F (2 x 2) the 3D gradient is
// F3(s) = [[F, 0], [0, s]], with the out-of-plane stretch s > 0 the root of
//   P_33(F3(s)) = dPsi/ds = 0,
// found by Newton on s (dP_33/ds = A_3333 > 0 for a law convex in s).  The
// 2D energy is Psi(F3(s)); by the envelope theorem its stress is the
// in-plane block of the 3D P at F3(s), and its tangent is the in-plane block
// condensed on s:
//   A2_ab = A_ab - A_a,33 A_33,b / A_33,33   (a, b in-plane pairs iJ),
// the in-plane F_i3, F_3J staying zero (an isotropic law is even in them
// at such an F, so they do not couple).  At F = I this gives the plane
// stress elasticity: lambda* = 2 lambda mu / (lambda + 2 mu), mu unchanged,
// so the small-deformation path (small_strain_material) assembles plane
// stress with no code of its own.  The 3D methods are the wrapped law's.
#pragma once

#include <memory>

#include "materials/hyperelastic.hpp"

namespace igac {

class PlaneStressLaw final : public HyperelasticLaw {
 public:
  explicit PlaneStressLaw(std::shared_ptr<const HyperelasticLaw> law);
  std::string name() const override { return law_->name(); }
  bool evaluate(const Eigen::Matrix2d& F, Eigen::Matrix2d& P, Eigen::Matrix4d* A) const override;
  bool evaluate(const Eigen::Matrix3d& F, Eigen::Matrix3d& P, Eigen::Matrix<double, 9, 9>* A) const override {
    return law_->evaluate(F, P, A);
  }
  double energy(const Eigen::Matrix2d& F) const override;
  double energy(const Eigen::Matrix3d& F) const override { return law_->energy(F); }
  // s with P_33(diag(F, s)) = 0; NaN when F is inadmissible or no root is found.
  double out_of_plane_stretch(const Eigen::Matrix2d& F) const override;
  const HyperelasticLaw& law() const { return *law_; }

 private:
  std::shared_ptr<const HyperelasticLaw> law_;
  double thinning_ = 0;  // lambda / (lambda + 2 mu) of the law at F = I: the start of the stretch's Newton
};

}  // namespace igac
