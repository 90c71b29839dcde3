// SPDX-License-Identifier: BSD-3-Clause
#include "materials/neo_hookean.hpp"

#include <cmath>

namespace igac {

NeoHookean::NeoHookean(const MaterialParameters& p)
    : lambda_(p.lambda()), mu_(p.mu()), iso_(MooneyRivlin::isochoric_part(mu_ / 2, 0)) {}

VolumetricValues NeoHookean::volumetric(double J) const {
  const double K = lambda_ + 2 * mu_ / 3;
  return {0.25 * K * (J * J - 1 - 2 * std::log(J)), 0.5 * K * (J - 1 / J), 0.5 * K * (1 + 1 / (J * J))};
}

template <int dim>
double NeoHookean::energy(const DimMatrix<dim>& F) const {
  const double lnJ = std::log(F.determinant());
  // I_C - 3 = tr(F^T F) - dim, also in plane strain where C_33 = 1.
  return 0.5 * mu_ * (F.squaredNorm() - dim) - mu_ * lnJ + 0.5 * lambda_ * lnJ * lnJ;
}

template <int dim>
void NeoHookean::stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const {
  const DimMatrix<dim> Finv_T = F.inverse().transpose();
  const double lnJ = std::log(F.determinant());
  P = mu_ * F + (lambda_ * lnJ - mu_) * Finv_T;
}

template <int dim>
void NeoHookean::tangent(const DimMatrix<dim>& F, TangentMatrix<dim>& A) const {
  const DimMatrix<dim> Fi = F.inverse();
  const double lnJ = std::log(F.determinant());
  const double geo = mu_ - lambda_ * lnJ;
  for (int i = 0; i < dim; ++i)
    for (int J = 0; J < dim; ++J)
      for (int k = 0; k < dim; ++k)
        for (int L = 0; L < dim; ++L)
          A(i * dim + J, k * dim + L) = geo * Fi(J, k) * Fi(L, i) + lambda_ * Fi(J, i) * Fi(L, k);
  A.diagonal().array() += mu_;  // mu d_ik d_JL: the identity in this layout
}

template class HyperelasticAdapter<NeoHookean>;

}  // namespace igac
