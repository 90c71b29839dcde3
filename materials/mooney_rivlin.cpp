// SPDX-License-Identifier: BSD-3-Clause
#include "materials/mooney_rivlin.hpp"

#include <cmath>
#include <fmt/format.h>

namespace igac {

MaterialParameters MooneyRivlin::small_strain_equivalent(const MaterialParameters& p) {
  const double mu = 2 * (p.value("C10") + p.value("C01")), K = p.value("bulk_modulus");
  return {9 * K * mu / (3 * K + mu), (3 * K - 2 * mu) / (2 * (3 * K + mu)), {}};
}

MooneyRivlin::MooneyRivlin(const MaterialParameters& p)
    : c10_(p.value("C10")), c01_(p.value("C01")), bulk_(p.value("bulk_modulus")) {
  if (!(c10_ + c01_ > 0))
    throw MaterialParameterError("C10", fmt::format("C10 + C01 = {} must be positive (the shear modulus is 2 (C10 + C01))",
                                                    c10_ + c01_));
}

namespace {

// The invariants of the 3D C of F (plane strain: C_33 = 1 outside the block).
template <int dim>
struct Invariants {
  DimMatrix<dim> C;
  double I1, I2, J;
  explicit Invariants(const DimMatrix<dim>& F) : C(F.transpose() * F), J(F.determinant()) {
    constexpr double out_of_plane = 3 - dim;  // C_33 = 1 in plane strain
    I1 = C.trace() + out_of_plane;
    I2 = 0.5 * (I1 * I1 - (C * C).trace() - out_of_plane);
  }
};

}  // namespace

template <int dim>
double MooneyRivlin::energy(const DimMatrix<dim>& F) const {
  const Invariants<dim> v(F);
  return c10_ * (std::pow(v.J, -2.0 / 3) * v.I1 - 3) + c01_ * (std::pow(v.J, -4.0 / 3) * v.I2 - 3) +
         0.5 * bulk_ * (v.J - 1) * (v.J - 1);
}

template <int dim>
void MooneyRivlin::stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const {
  const Invariants<dim> v(F);
  const double psi1 = c10_ * std::pow(v.J, -2.0 / 3), psi2 = c01_ * std::pow(v.J, -4.0 / 3);
  const double psiJ = -2.0 / 3 * psi1 * v.I1 / v.J - 4.0 / 3 * psi2 * v.I2 / v.J + bulk_ * (v.J - 1);
  P = 2 * psi1 * F + 2 * psi2 * (v.I1 * F - F * v.C) + psiJ * v.J * F.inverse().transpose();
}

template <int dim>
void MooneyRivlin::tangent(const DimMatrix<dim>& F, TangentMatrix<dim>& A) const {
  const Invariants<dim> v(F);
  const double J = v.J;
  const double psi1 = c10_ * std::pow(J, -2.0 / 3), psi2 = c01_ * std::pow(J, -4.0 / 3);
  const double psiJ = -2.0 / 3 * psi1 * v.I1 / J - 4.0 / 3 * psi2 * v.I2 / J + bulk_ * (J - 1);
  const DimMatrix<dim> Fi = F.inverse(), FiT = Fi.transpose();
  const DimMatrix<dim> G = v.I1 * F - F * v.C;  // dI2/dF / 2
  const DimMatrix<dim> FFt = F * F.transpose();
  // Derivatives of the coefficients with respect to F:
  //   dPsi_1/dF = -2/3 Psi_1 F^{-T},  dPsi_2/dF = -4/3 Psi_2 F^{-T},
  //   dPsi_J/dF = -4/3 Psi_1/J F - 8/3 Psi_2/J G
  //               + (10/9 Psi_1 I1/J^2 + 28/9 Psi_2 I2/J^2 + K) J F^{-T}.
  const DimMatrix<dim> dpsi1 = -2.0 / 3 * psi1 * FiT, dpsi2 = -4.0 / 3 * psi2 * FiT;
  const DimMatrix<dim> dpsiJ = -4.0 / 3 * psi1 / J * F - 8.0 / 3 * psi2 / J * G +
                               (10.0 / 9 * psi1 * v.I1 / (J * J) + 28.0 / 9 * psi2 * v.I2 / (J * J) + bulk_) * J * FiT;
  for (int i = 0; i < dim; ++i)
    for (int Jd = 0; Jd < dim; ++Jd)
      for (int k = 0; k < dim; ++k)
        for (int L = 0; L < dim; ++L) {
          const double d_ik = i == k, d_JL = Jd == L;
          // d(I1 F - F C)_iJ / dF_kL = 2 F_kL F_iJ + I1 d_ik d_JL - d_ik C_LJ - F_iL F_kJ - (F F^T)_ik d_JL
          const double dG = 2 * F(k, L) * F(i, Jd) + v.I1 * d_ik * d_JL - d_ik * v.C(L, Jd) - F(i, L) * F(k, Jd) -
                            FFt(i, k) * d_JL;
          // d(J F^{-T})_iJ / dF_kL = J (F^{-1}_Lk F^{-1}_Ji - F^{-1}_Jk F^{-1}_Li)
          const double dJFiT = J * (Fi(L, k) * Fi(Jd, i) - Fi(Jd, k) * Fi(L, i));
          A(i * dim + Jd, k * dim + L) = 2 * F(i, Jd) * dpsi1(k, L) + 2 * psi1 * d_ik * d_JL + 2 * G(i, Jd) * dpsi2(k, L) +
                                         2 * psi2 * dG + J * FiT(i, Jd) * dpsiJ(k, L) + psiJ * dJFiT;
        }
}

template double MooneyRivlin::energy<2>(const DimMatrix<2>&) const;
template double MooneyRivlin::energy<3>(const DimMatrix<3>&) const;
template void MooneyRivlin::stress<2>(const DimMatrix<2>&, DimMatrix<2>&) const;
template void MooneyRivlin::stress<3>(const DimMatrix<3>&, DimMatrix<3>&) const;
template void MooneyRivlin::tangent<2>(const DimMatrix<2>&, TangentMatrix<2>&) const;
template void MooneyRivlin::tangent<3>(const DimMatrix<3>&, TangentMatrix<3>&) const;
template class HyperelasticAdapter<MooneyRivlin>;

}  // namespace igac
