// SPDX-License-Identifier: BSD-3-Clause
#include "engine/load_curve.hpp"

#include <algorithm>
#include <cmath>

namespace igac {

std::vector<double> curve_corners(const std::vector<const LoadCurve*>& curves) {
  std::vector<double> out;
  for (const LoadCurve* c : curves)
    if (c)
      for (const auto& p : c->points())
        if (p[0] > 0) out.push_back(p[0]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (out.empty()) out.push_back(1.0);
  return out;
}

std::vector<double> step_times(const std::vector<double>& corners, int steps_per_unit_time) {
  std::vector<double> out;
  double a = 0;
  for (const double b : corners) {
    // (1e-9: a length that is a whole number of unit steps up to round-off takes that many)
    const int n = std::max(1, int(std::ceil((b - a) * steps_per_unit_time - 1e-9)));
    for (int k = 1; k < n; ++k) out.push_back(a + (b - a) * k / n);
    out.push_back(b);
    a = b;
  }
  return out;
}

}  // namespace igac
