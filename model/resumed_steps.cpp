// SPDX-License-Identifier: BSD-3-Clause
#include "model/resumed_steps.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "engine/load_curve.hpp"
#include "engine/load_stepping.hpp"

namespace igac {

// The slack of a time (absolute) or an increment (relative) read back
// against the bounds the driver keeps: it ends a run within 1e-12 of its
// last corner (engine/load_stepping.cpp), and rounds an increment it grows.
constexpr double kScheduleSlack = 1e-12;

// The earlier run's steps are steps this case takes (a state file's t and
// dt are read back, and the driver believed them: a t of NaN or 1e300 ended
// the run at once as "converged", a dt of 0 or below ran it forever).  In
// small deformation the times are the case's own (engine/load_curve.hpp,
// step_times); in large deformation they increase inside the case's span,
// and the next increment is one its [loading] gives: at least the smallest
// it cuts back to (or the first, when that is smaller), at most the largest
// grown once; a run that has reached the end takes no increment more.
std::optional<OffSchedule> off_schedule(const CaseSpec& spec, const std::vector<StepState>& steps) {
  const std::vector<double> corners = curve_corners(spec.load_curves());
  const double end = corners.back();
  const std::vector<double> times = spec.finite_strain() ? std::vector<double>{} : step_times(corners, spec.loading.steps);
  const LoadingSpec& l = spec.loading;
  const double first = l.first_increment > 0 ? l.first_increment : 1.0 / l.steps;
  const double lo = std::min(l.min_increment, first), hi = l.max_increment * LoadSteppingOptions{}.growth;
  double before = 0;
  for (const StepState& s : steps) {
    const auto bad = [&](std::string why) { return OffSchedule{s.step, std::move(why)}; };
    const LoadSteppingState& d = s.driver;
    if (!times.empty()) {
      if (size_t(s.step) > times.size() || !(d.t == times[size_t(s.step) - 1]))
        return bad(fmt::format("t = {}, where this case has {}", d.t,
                              size_t(s.step) > times.size() ? fmt::format("{} steps", times.size())
                                                            : fmt::format("step {} at t = {}", s.step, times[size_t(s.step) - 1])));
    } else if (!(d.t > before && d.t <= end + kScheduleSlack)) {
      return bad(fmt::format("t = {}, where step {} lies in ({}, {}]", d.t, s.step, before, end));
    }
    if (!(s.record.load_factor == d.t && s.point.load_factor == d.t))
      return bad(fmt::format("its step's record is at t = {} and {}, its state at {}", s.record.load_factor,
                            s.point.load_factor, d.t));
    if (spec.finite_strain()) {
      const double low = d.t < end - kScheduleSlack ? lo : 0;  // (the last step's dt is what remained of the span)
      if (!(d.dt > 0 && d.dt >= low * (1 - kScheduleSlack) && d.dt <= hi * (1 + kScheduleSlack)))
        return bad(fmt::format("the next increment dt = {} lies outside [{}, {}], where [loading] puts it", d.dt,
                              low, hi));
      if (!(d.dt_old >= 0 && d.dt_old <= l.max_increment * (1 + kScheduleSlack)))
        return bad(fmt::format("the last increment dt_old = {} lies outside [0, {}]", d.dt_old, l.max_increment));
    }
    if (!d.x.allFinite() || !d.x_old.allFinite()) return bad("its unknowns hold a number that is not finite");
    before = d.t;
  }
  return std::nullopt;
}

}  // namespace igac
