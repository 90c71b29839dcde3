// SPDX-License-Identifier: BSD-3-Clause
// Test geometry helpers shared by several test files.
#pragma once

#include <Eigen/Dense>
#include <random>

#include "engine/spline/nurbs_patch.hpp"

namespace igac_test {

// Moves every control point not on the boundary by up to `amount` in each
// coordinate, drawn from a seeded uniform distribution (weights untouched):
// a curved, non-affine map that is still polynomial in the parameters when
// the patch is, with the boundary (and so its faces) unchanged.
inline igac::NurbsPatch distort_interior(const igac::NurbsPatch& p, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shift(-amount, amount);
  Eigen::MatrixXd P = p.points();
  for (int i = 0; i < p.num_control_points(); ++i) {
    const auto m = p.multi_index(i);
    bool interior = true;
    for (int d = 0; d < p.param_dim(); ++d) interior = interior && m[d] > 0 && m[d] + 1 < p.num_basis(d);
    if (interior)
      for (int c = 0; c < p.space_dim(); ++c) P(i, c) += shift(rng);
  }
  return igac::NurbsPatch(p.all_knots(), P, p.weights());
}

}  // namespace igac_test
