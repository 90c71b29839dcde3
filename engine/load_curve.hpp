// SPDX-License-Identifier: BSD-3-Clause
// A load curve: the factor f(t) a load is multiplied by at pseudo-time t,
// piecewise linear through the points (t_0, f_0), ..., (t_n, f_n), t_0 = 0
// and the times strictly increasing, held at f_n after t_n.  Going back
// down is unloading.  Between corners t_i <= t <= t_i+1:
//   f(t) = f_i + (t - t_i) / (t_i+1 - t_i) (f_i+1 - f_i),
// so f(t_i) = f_i exactly.
//
// A curve without points is the classic ramp f(t) = t, what every load of a
// case without curves follows from t = 0 to 1 (bit for bit what the
// load-stepping driver did before curves: the factor is t itself).  In a
// case where some load has a curve, the loads without one follow
// ramp_and_hold(): 0 -> 1 over [0, 1], then 1.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace igac {

class LoadCurve {
 public:
  LoadCurve() = default;  // f(t) = t
  explicit LoadCurve(std::vector<std::array<double, 2>> points) : points_(std::move(points)) {}
  static LoadCurve ramp_and_hold() { return LoadCurve(std::vector<std::array<double, 2>>{{0.0, 0.0}, {1.0, 1.0}}); }

  double operator()(double t) const {
    if (points_.empty()) return t;
    if (t <= points_.front()[0]) return points_.front()[1];
    for (std::size_t i = 0; i + 1 < points_.size(); ++i) {
      const auto &a = points_[i], &b = points_[i + 1];
      if (t <= b[0]) return t == b[0] ? b[1] : a[1] + (t - a[0]) / (b[0] - a[0]) * (b[1] - a[1]);
    }
    return points_.back()[1];
  }
  bool has_points() const { return !points_.empty(); }
  const std::vector<std::array<double, 2>>& points() const { return points_; }
  // The time of the last point (the ramp: 1).
  double end_time() const { return points_.empty() ? 1.0 : points_.back()[0]; }

 private:
  std::vector<std::array<double, 2>> points_;
};

// The corners of several curves: every point's time after 0, sorted, once
// each; the last is where a run along them ends.  No curve with points: {1}.
std::vector<double> curve_corners(const std::vector<const LoadCurve*>& curves);

// The steps of the segment [a, b] at `per_unit_time` steps per unit of
// time: ceil((b - a) * per_unit_time), at least 1.  A double: it may exceed
// any integer type (a case file's check compares it with its bound).
double segment_steps(double a, double b, double per_unit_time);
// The steps of step_times(corners, per_unit_time), summed in double.
double count_step_times(const std::vector<double>& corners, double per_unit_time);

// Step times along [0, corners.back()]: each segment between corners cut in
// segment_steps equal steps, every corner a step's end (exactly the
// corner's value).  Throws std::length_error beyond kMaxLoadSteps in all.
std::vector<double> step_times(const std::vector<double>& corners, int steps_per_unit_time);

// The most load steps a run takes (each writes its ParaView step and state
// file): what the case reader allows [loading] steps per unit time on
// [0, 1], and in all along the curves.
inline constexpr double kMaxLoadSteps = 100000;

}  // namespace igac
