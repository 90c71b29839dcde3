// SPDX-License-Identifier: BSD-3-Clause
// The one stopwatch of the timings igac reports (summary.json's timing_s,
// the solver statistics): wall-clock seconds on the steady clock.
//
//   Stopwatch clock;               // starts now
//   ...; a = clock.seconds();      // seconds since the start; keeps running
//   clock.restart(); ...; b = clock.seconds();
#pragma once

#include <chrono>

namespace igac {

class Stopwatch {
 public:
  using Clock = std::chrono::steady_clock;
  Stopwatch() : start_(Clock::now()) {}
  // Seconds since construction or the last restart().
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  void restart() { start_ = Clock::now(); }

 private:
  Clock::time_point start_;
};

}  // namespace igac
