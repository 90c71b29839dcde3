// SPDX-License-Identifier: BSD-3-Clause
// Saint Venant-Kirchhoff material: linear elasticity in the Green-Lagrange
// strain (Holzapfel, Nonlinear Solid Mechanics, eq. 6.151; Wriggers,
// Nonlinear FEM, eq. 3.114).  The worked example of materials/README.md.
//
//   E = (F^T F - I)/2,   Psi = lambda/2 (tr E)^2 + mu E : E,
//   S = dPsi/dE = lambda tr(E) I + 2 mu E,   P = F S,
//   A_iJkL = d_ik S_JL                                       (geometric term)
//            + lambda F_iJ F_kL + mu (F F^T)_ik d_JL + mu F_iL F_kJ  (material term,
//                                         F_iM F_kN C_MJNL with C the Lame tensor).
// At F = I it is the linear elasticity tensor; it is objective (depends on F
// through C = F^T F only).  Plane strain: E_33 = 0, the same code with dim = 2.
//
// Psi stays finite as J -> 0 (SVK is not polyconvex and softens in strong
// compression), so det F <= 0 is declared inadmissible here rather than left
// to the energy: an inverted element is a failed step, as for Neo-Hookean.
#pragma once

#include <string_view>

#include "materials/hyperelastic.hpp"

namespace igac {

class SaintVenantKirchhoff : public YoungPoissonParameters {
 public:
  static constexpr std::string_view kName = "saint_venant_kirchhoff";
  static constexpr bool kRequiresPositiveJ = true;
  explicit SaintVenantKirchhoff(const MaterialParameters& parameters);

  template <int dim>
  double energy(const DimMatrix<dim>& F) const;
  template <int dim>
  void stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const;
  template <int dim>
  void tangent(const DimMatrix<dim>& F, TangentMatrix<dim>& A) const;

 private:
  template <int dim>
  DimMatrix<dim> second_piola(const DimMatrix<dim>& E) const;
  double lambda_, mu_;
};

// Compiled once, in saint_venant_kirchhoff.cpp, together with the law's methods.
extern template class HyperelasticAdapter<SaintVenantKirchhoff>;

}  // namespace igac
