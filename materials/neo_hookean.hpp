// SPDX-License-Identifier: BSD-3-Clause
// Compressible Neo-Hookean material (Holzapfel, Nonlinear Solid Mechanics,
// eq. 6.148; Wriggers, Nonlinear FEM, eq. 3.118; the law of the paper's
// large-deformation benchmarks, section 4.3):
//
//   Psi = mu/2 (I_C - 3) - mu ln J + lambda/2 (ln J)^2,   I_C = tr(F^T F), J = det F.
//
// Derivatives, with dJ/dF = J F^{-T} and dF^{-1}_Ji / dF_kL = -F^{-1}_Jk F^{-1}_Li:
//   P = mu (F - F^{-T}) + lambda ln J F^{-T},
//   A_iJkL = mu d_ik d_JL + (mu - lambda ln J) F^{-1}_Jk F^{-1}_Li
//            + lambda F^{-1}_Ji F^{-1}_Lk.
// At F = I: A = lambda d_iJ d_kL + mu (d_ik d_JL + d_iL d_Jk), the linear
// elasticity tensor, so the law linearises to LinearElasticLaw.
//
// Plane strain (2D): F_33 = 1, so I_C = tr(C_2x2) + 1 (I_C - 3 = tr C_2x2 - 2)
// and J = det F_2x2; the 3D formulas restricted to the in-plane block are
// exactly the 2D ones, i.e. the same code with dim = 2.
//
// Requires J > 0: ln J is undefined otherwise, and Psi -> +inf as J -> 0+.
//
// Split for the mixed formulation (VolumetricSplitLaw): the decoupled
// Neo-Hookean solid of Simo and Miehe (1992), with the same mu and the bulk
// modulus K = lambda + 2 mu / 3 of (E, nu):
//   W_iso = mu/2 (I1bar - 3)    (Mooney-Rivlin with C10 = mu/2, C01 = 0),
//   U(J)  = K/4 (J^2 - 1 - 2 ln J),  U' = K/2 (J - 1/J),  U'' = K/2 (1 + 1/J^2) > 0.
// It linearises at F = I to the same (lambda, mu) as the coupled law above;
// at finite strain the two differ (the coupled law has no isochoric split).
#pragma once

#include <string_view>

#include "materials/hyperelastic.hpp"
#include "materials/mooney_rivlin.hpp"

namespace igac {

class NeoHookean : public YoungPoissonParameters {
 public:
  static constexpr std::string_view kName = "neo_hookean";
  static constexpr bool kRequiresPositiveJ = true;
  explicit NeoHookean(const MaterialParameters& parameters);

  template <int dim>
  double energy(const DimMatrix<dim>& F) const;
  template <int dim>
  void stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const;
  template <int dim>
  void tangent(const DimMatrix<dim>& F, TangentMatrix<dim>& A) const;

  template <int dim>
  double isochoric_energy(const DimMatrix<dim>& F) const { return iso_.energy<dim>(F); }
  template <int dim>
  void isochoric_stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const { iso_.stress<dim>(F, P); }
  template <int dim>
  void isochoric_tangent(const DimMatrix<dim>& F, TangentMatrix<dim>& A) const { iso_.tangent<dim>(F, A); }
  VolumetricValues volumetric(double J) const;

 private:
  double lambda_, mu_;
  MooneyRivlin iso_;  // mu/2 (I1bar - 3)
};

// Compiled once, in neo_hookean.cpp, together with the law's methods.
extern template class HyperelasticAdapter<NeoHookean>;

}  // namespace igac
