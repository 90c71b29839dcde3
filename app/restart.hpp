// SPDX-License-Identifier: BSD-3-Clause
// igac run CASE --restart DIR [--from-step N]: continue an earlier run of
// the same case from the state it wrote after step N (the last one by
// default), so that the result is the one an uninterrupted run gives, bit
// for bit (docs/design.md, "Restart").  The earlier run's per-step state
// files (io/state_file.hpp) give the steps' records and the driver's state;
// its .vtu files of steps 0..N are copied into the new output, whose .pvd
// goes on from there.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/vtk_output.hpp"
#include "model/run_result.hpp"

namespace igac {

struct RestartOptions {
  std::string dir;               // the earlier run's output folder (empty: no restart)
  std::optional<int> from_step;  // the step to continue after (none: the last one written)
  int stop_after_step = 0;       // > 0: stop once this many steps are done
};

// The steps 1..N of the earlier run in options.dir, checked: an igac output
// of the same case file (summary.json's input.fnv1a64 equals the hash of
// `case_path`), with its state files.  Throws InputError in one line.
std::vector<StepState> read_earlier_steps(const std::string& case_path, const RestartOptions& options);

// Copies the earlier run's files of steps 0..n (the .vtu listed in its
// solution.pvd, when it has one and `vtk`, and the state files) into
// `staging`; returns the .pvd's steps among them.
std::vector<VtkStep> adopt_earlier_steps(const std::string& dir, const std::string& staging, int n, bool vtk);

}  // namespace igac
