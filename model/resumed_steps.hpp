// SPDX-License-Identifier: BSD-3-Clause
// Whether the steps an earlier run wrote (its state files, read back by a
// restart) are steps this case takes: what the restart believes is then
// only what the case itself could have produced.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "model/case_spec.hpp"
#include "model/run_result.hpp"

namespace igac {

// The first step off the case's schedule, and why ("t = nan, where step 3
// lies in (0.25, 1]").
struct OffSchedule {
  int step = 0;
  std::string why;
};

// Checks each step's time (small deformation: the case's own step times;
// large deformation: increasing, inside the span), its next and last
// increments (inside what [loading] gives), that its record and load-curve
// point stand at its time, and that its unknowns are finite.
std::optional<OffSchedule> off_schedule(const CaseSpec& spec, const std::vector<StepState>& steps);

}  // namespace igac
