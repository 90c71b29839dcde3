// SPDX-License-Identifier: BSD-3-Clause
// Linear elasticity written as a law of F, for the nonlinear driver: a
// small-strain material inside the total-Lagrangian machinery (the linear
// assembler keeps using materials/linear_elastic.hpp and never calls this).
//
//   eps = sym(F - I) = (F + F^T)/2 - I,
//   Psi = 1/2 eps : C : eps = lambda/2 (tr eps)^2 + mu eps : eps,
//   P   = sigma(eps) = lambda tr(eps) I + 2 mu eps        (symmetric),
//   A_iJkL = C_iJkL = lambda d_iJ d_kL + mu (d_ik d_JL + d_iL d_Jk)  (constant).
// P = dPsi/dF holds because sigma is symmetric, so sigma : dF = sigma : d eps.
// In 2D plane strain eps_33 = 0 and the same formulas hold with dim = 2.
//
// Not objective: a finite rotation Q gives eps(Q) = sym(Q) - I != 0, so
// Psi(QF) != Psi(F) and P(QF) != Q P(F); the error is second order in the
// rotation angle, which is why it is only a small-deformation model.  Every F
// is admissible (no det F > 0 requirement) except a non-finite one.
#pragma once

#include <string_view>

#include "materials/hyperelastic.hpp"

namespace igac {

class LinearElasticLaw : public YoungPoissonParameters {
 public:
  static constexpr std::string_view kName = "linear_elastic";
  static constexpr bool kRequiresPositiveJ = false;
  explicit LinearElasticLaw(const MaterialParameters& parameters);

  template <int dim>
  double energy(const DimMatrix<dim>& F) const;
  template <int dim>
  void stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const;
  template <int dim>
  void tangent(const DimMatrix<dim>& F, TangentMatrix<dim>& A) const;

 private:
  double lambda_, mu_;
};

// Compiled once, in linear_elastic_law.cpp, together with the law's methods.
extern template class HyperelasticAdapter<LinearElasticLaw>;

}  // namespace igac
