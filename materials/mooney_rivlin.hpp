// SPDX-License-Identifier: BSD-3-Clause
// Compressible Mooney-Rivlin rubber (Holzapfel, Nonlinear Solid Mechanics,
// eq. 6.148 with the isochoric split of 6.4; the usual law of O-ring and seal
// analyses):
//
//   Psi = C10 (I1bar - 3) + C01 (I2bar - 3) + K/2 (J - 1)^2,
//   I1bar = J^{-2/3} I1,  I2bar = J^{-4/3} I2,
//   I1 = tr C,  I2 = (I1^2 - tr C^2) / 2,  C = F^T F,  J = det F.
//
// Parameters (case file keys): C10, C01 (Pa, any sign, with C10 + C01 > 0)
// and bulk_modulus K > 0.  At small strain the law is linear elasticity with
// mu = 2 (C10 + C01) and the bulk modulus K; C01 = 0 is a neo-Hookean solid.
//
// Derivatives, with Psi_1 = dPsi/dI1 = C10 J^{-2/3}, Psi_2 = C01 J^{-4/3},
// Psi_J = -2/3 C10 J^{-5/3} I1 - 4/3 C01 J^{-7/3} I2 + K (J - 1), and
// dI1/dF = 2F, dI2/dF = 2 (I1 F - F C), dJ/dF = J F^{-T}:
//   P = 2 Psi_1 F + 2 Psi_2 (I1 F - F C) + Psi_J J F^{-T},
// and A = dP/dF by the product rule on each term (mooney_rivlin.cpp).
//
// Plane strain (2D): F_33 = 1 adds 1 to tr C and to tr C^2; the in-plane
// block of the 3D P and A is the same code with dim = 2 and these invariants.
// Requires J > 0.
//
// Split for the mixed formulation: the law is written as W_iso + U(J) with
// U = K/2 (J - 1)^2 (U'' = K > 0: convex), so the split is the law itself.
#pragma once

#include <string_view>

#include "materials/hyperelastic.hpp"

namespace igac {

class MooneyRivlin {
 public:
  static constexpr std::string_view kName = "mooney_rivlin";
  static constexpr bool kRequiresPositiveJ = true;
  static constexpr LawParameter kParameters[] = {
      {"C10", "first Mooney-Rivlin constant"},
      {"C01", "second Mooney-Rivlin constant"},
      {"bulk_modulus", "bulk modulus K", 0.0, std::numeric_limits<double>::infinity(), true, true},
  };
  // mu = 2 (C10 + C01), K: E = 9 K mu / (3 K + mu), nu = (3 K - 2 mu) / (2 (3 K + mu)).
  static MaterialParameters small_strain_equivalent(const MaterialParameters& p);
  // Throws MaterialParameterError unless C10 + C01 > 0.
  explicit MooneyRivlin(const MaterialParameters& parameters);

  template <int dim>
  double energy(const DimMatrix<dim>& F) const;
  template <int dim>
  void stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const;
  template <int dim>
  void tangent(const DimMatrix<dim>& F, TangentMatrix<dim>& A) const;

  // The split (VolumetricSplitLaw): W_iso = C10 (I1bar - 3) + C01 (I2bar - 3)
  // is the law with K = 0, U(J) = K/2 (J - 1)^2, so W_iso + U is the law.
  template <int dim>
  double isochoric_energy(const DimMatrix<dim>& F) const { return isochoric().energy<dim>(F); }
  template <int dim>
  void isochoric_stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const { isochoric().stress<dim>(F, P); }
  template <int dim>
  void isochoric_tangent(const DimMatrix<dim>& F, TangentMatrix<dim>& A) const { isochoric().tangent<dim>(F, A); }
  VolumetricValues volumetric(double J) const { return {0.5 * bulk_ * (J - 1) * (J - 1), bulk_ * (J - 1), bulk_}; }
  // The isochoric part alone, C10 (I1bar - 3) + C01 (I2bar - 3): also the
  // isochoric part of the decoupled Neo-Hookean split (neo_hookean.hpp).
  static MooneyRivlin isochoric_part(double c10, double c01) {
    MooneyRivlin m;
    m.c10_ = c10, m.c01_ = c01, m.bulk_ = 0;
    return m;
  }

 private:
  MooneyRivlin() = default;
  MooneyRivlin isochoric() const { return isochoric_part(c10_, c01_); }
  double c10_ = 0, c01_ = 0, bulk_ = 0;
};

extern template class HyperelasticAdapter<MooneyRivlin>;
extern template double MooneyRivlin::energy<2>(const DimMatrix<2>&) const;
extern template double MooneyRivlin::energy<3>(const DimMatrix<3>&) const;
extern template void MooneyRivlin::stress<2>(const DimMatrix<2>&, DimMatrix<2>&) const;
extern template void MooneyRivlin::stress<3>(const DimMatrix<3>&, DimMatrix<3>&) const;
extern template void MooneyRivlin::tangent<2>(const DimMatrix<2>&, TangentMatrix<2>&) const;
extern template void MooneyRivlin::tangent<3>(const DimMatrix<3>&, TangentMatrix<3>&) const;

}  // namespace igac
