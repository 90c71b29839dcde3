// SPDX-License-Identifier: BSD-3-Clause
#include "materials/saint_venant_kirchhoff.hpp"

namespace igac {

SaintVenantKirchhoff::SaintVenantKirchhoff(const MaterialParameters& p) : lambda_(p.lambda()), mu_(p.mu()) {}

namespace {
template <int dim>
DimMatrix<dim> green_lagrange(const DimMatrix<dim>& F) {
  return 0.5 * (F.transpose() * F - DimMatrix<dim>::Identity());
}
}  // namespace

template <int dim>
DimMatrix<dim> SaintVenantKirchhoff::second_piola(const DimMatrix<dim>& E) const {
  DimMatrix<dim> S = 2 * mu_ * E;
  S.diagonal().array() += lambda_ * E.trace();
  return S;
}

template <int dim>
double SaintVenantKirchhoff::energy(const DimMatrix<dim>& F) const {
  const DimMatrix<dim> E = green_lagrange<dim>(F);
  const double tr = E.trace();
  return 0.5 * lambda_ * tr * tr + mu_ * E.squaredNorm();
}

template <int dim>
void SaintVenantKirchhoff::stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const {
  P = F * second_piola<dim>(green_lagrange<dim>(F));
}

template <int dim>
void SaintVenantKirchhoff::tangent(const DimMatrix<dim>& F, TangentMatrix<dim>& A) const {
  const DimMatrix<dim> S = second_piola<dim>(green_lagrange<dim>(F));
  const DimMatrix<dim> b = F * F.transpose();
  for (int i = 0; i < dim; ++i)
    for (int J = 0; J < dim; ++J)
      for (int k = 0; k < dim; ++k)
        for (int L = 0; L < dim; ++L)
          A(i * dim + J, k * dim + L) = lambda_ * F(i, J) * F(k, L) + mu_ * F(i, L) * F(k, J);
  // The Kronecker terms touch only some entries: add them without branches.
  for (int i = 0; i < dim; ++i)
    for (int J = 0; J < dim; ++J)
      for (int L = 0; L < dim; ++L) A(i * dim + J, i * dim + L) += S(J, L);  // d_ik S_JL
  for (int i = 0; i < dim; ++i)
    for (int k = 0; k < dim; ++k)
      for (int J = 0; J < dim; ++J) A(i * dim + J, k * dim + J) += mu_ * b(i, k);  // mu b_ik d_JL
}

template class HyperelasticAdapter<SaintVenantKirchhoff>;

}  // namespace igac
