// SPDX-License-Identifier: BSD-3-Clause
// What the built-in shapes (one file each in this folder) share: Bezier
// knot vectors, the circle weight, and the positive-length check.
#pragma once

#include <cmath>
#include <fmt/format.h>

#include "engine/geometry/shapes.hpp"

namespace igac::shape_support {

inline const double kHalfSqrt2 = std::sqrt(0.5);

inline KnotVector bezier(int p) { return KnotVector::uniform(p, 1); }

inline void check_positive(double v, const char* what) {
  if (!(v > 0) || !std::isfinite(v)) throw SplineError(fmt::format("{} must be positive, got {}", what, v));
}

}  // namespace igac::shape_support
