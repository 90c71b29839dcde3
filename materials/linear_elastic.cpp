// SPDX-License-Identifier: BSD-3-Clause
#include "materials/linear_elastic.hpp"

#include <cmath>
#include <fmt/format.h>

namespace igac {

LinearElastic::LinearElastic(double E, double nu) : E_(E), nu_(nu) {
  if (!(E > 0) || !std::isfinite(E))
    throw MaterialError(fmt::format("E = {} must be positive (Young's modulus)", E));
  if (!(nu > -1 && nu < 0.5))
    throw MaterialError(fmt::format("nu = {} must lie in (-1, 0.5) (Poisson's ratio; 0.5 is incompressible)", nu));
}

}  // namespace igac
