// SPDX-License-Identifier: BSD-3-Clause
#include "model/deformation_check.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace igac {

std::optional<std::string> small_deformation_warning(const Model& m, const RunResult& r) {
  if (m.spec.finite_strain() || r.u.size() == 0 || !r.u.allFinite()) return std::nullopt;
  const Eigen::MatrixXd& X = m.body.points();
  const double size = (X.colwise().maxCoeff() - X.colwise().minCoeff()).maxCoeff();
  const double largest = r.u.rowwise().norm().maxCoeff();
  if (!(size > 0) || !(largest > kSmallDeformationLimit * size)) return std::nullopt;
  return fmt::format("{}: the largest displacement, {:.3g}, is {:.0f} % of the body's size {:.3g}: far beyond small "
                     "deformation (linear_elastic assumes displacements, rotations and the obstacle's approach small "
                     "beside the body, here at most {:.0f} %), the result is not to be trusted; for large deformation "
                     "give [material] model a hyperelastic law (neo_hookean, saint_venant_kirchhoff, mooney_rivlin)",
                     m.spec.path, largest, 100 * largest / size, size, 100 * kSmallDeformationLimit);
}

}  // namespace igac
