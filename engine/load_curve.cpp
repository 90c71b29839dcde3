// SPDX-License-Identifier: BSD-3-Clause
#include "engine/load_curve.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <fmt/format.h>

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

double segment_steps(double a, double b, double per_unit_time) {
  // (1e-9: a length that is a whole number of unit steps up to round-off takes that many)
  return std::max(1.0, std::ceil((b - a) * per_unit_time - 1e-9));
}

double count_step_times(const std::vector<double>& corners, double per_unit_time) {
  double n = 0, a = 0;
  for (const double b : corners) {
    n += segment_steps(a, b, per_unit_time);
    a = b;
  }
  return n;
}

std::vector<double> step_times(const std::vector<double>& corners, int steps_per_unit_time) {
  if (!(count_step_times(corners, steps_per_unit_time) <= kMaxLoadSteps))  // (an int would overflow first)
    throw std::length_error(fmt::format("step_times: more than {:g} load steps", kMaxLoadSteps));
  std::vector<double> out;
  double a = 0;
  for (const double b : corners) {
    const int n = int(segment_steps(a, b, steps_per_unit_time));
    for (int k = 1; k < n; ++k) out.push_back(a + (b - a) * k / n);
    out.push_back(b);
    a = b;
  }
  return out;
}

}  // namespace igac
