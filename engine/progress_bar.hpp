// SPDX-License-Identifier: BSD-3-Clause
// The progress bar of a run's step lines and heartbeat,
// "[########------------] 40 %", shown only where a person watches: when
// stderr is a terminal (not a log or a pipe, whose lines stay plain).
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

namespace igac {

// The bar at fraction `done` (clamped to [0, 1]), `width` cells.
inline std::string progress_bar(double done, int width = 20) {
  const double f = std::clamp(std::isfinite(done) ? done : 0.0, 0.0, 1.0);
  const int full = int(std::floor(f * width + 1e-9));
  return fmt::format("[{}{}] {:.0f} %", std::string(size_t(full), '#'), std::string(size_t(width - full), '-'),
                     std::floor(100 * f + 1e-9));
}

inline bool stderr_is_terminal() {
  static const bool terminal = isatty(STDERR_FILENO) == 1;
  return terminal;
}

// "  " and the bar on a terminal, "" elsewhere: the end of a step line.
inline std::string progress_suffix(double done) {
  return stderr_is_terminal() ? "  " + progress_bar(done) : std::string();
}

}  // namespace igac
