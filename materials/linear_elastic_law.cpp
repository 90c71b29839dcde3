// SPDX-License-Identifier: BSD-3-Clause
#include "materials/linear_elastic_law.hpp"

namespace igac {

LinearElasticLaw::LinearElasticLaw(const MaterialParameters& p) : lambda_(p.lambda()), mu_(p.mu()) {}

namespace {
template <int dim>
DimMatrix<dim> small_strain(const DimMatrix<dim>& F) {
  return 0.5 * (F + F.transpose()) - DimMatrix<dim>::Identity();
}
}  // namespace

template <int dim>
double LinearElasticLaw::energy(const DimMatrix<dim>& F) const {
  const DimMatrix<dim> eps = small_strain<dim>(F);
  const double tr = eps.trace();
  return 0.5 * lambda_ * tr * tr + mu_ * eps.squaredNorm();
}

template <int dim>
void LinearElasticLaw::stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const {
  const DimMatrix<dim> eps = small_strain<dim>(F);
  P = 2 * mu_ * eps;
  P.diagonal().array() += lambda_ * eps.trace();
}

template <int dim>
void LinearElasticLaw::tangent(const DimMatrix<dim>&, TangentMatrix<dim>& A) const {
  A.setZero();
  for (int i = 0; i < dim; ++i)
    for (int J = 0; J < dim; ++J) {
      A(i * dim + i, J * dim + J) += lambda_;  // lambda d_iJ d_kL (with i = J, k = L)
      A(i * dim + J, i * dim + J) += mu_;      // mu d_ik d_JL
      A(i * dim + J, J * dim + i) += mu_;      // mu d_iL d_Jk
    }
}

template class HyperelasticAdapter<LinearElasticLaw>;

}  // namespace igac
