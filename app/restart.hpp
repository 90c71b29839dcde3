// SPDX-License-Identifier: BSD-3-Clause
// igac run CASE --restart DIR [--from-step N]: continue an earlier run of
// the same case, with the same options, from the state it wrote after step
// N (the last one by default), so that the result is the one an
// uninterrupted run gives, bit for bit (docs/design.md, "Restart").  The
// earlier run's per-step state files (io/state_file.hpp) give the steps'
// records and the driver's state; its .vtu files of steps 0..N are taken
// into the new output, whose .pvd goes on from there.
//
// Where the state is: a run writes into a hidden staging folder beside DIR
// (app/output_folder.hpp) that becomes DIR when it ends.  A run killed or
// stopped before (SIGKILL, a power loss, SIGTERM, Ctrl-C) leaves that
// folder, with the state files and ParaView files of its completed steps and
// no summary.json; DIR keeps the earlier finished run.  --restart DIR takes
// such a stopped run beside DIR when there is one (it is the later: a run
// into DIR removes the stopped ones when it starts), else DIR itself.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/vtk_output.hpp"
#include "model/case_spec.hpp"
#include "model/run_result.hpp"

namespace igac {

struct RestartOptions {
  std::string dir;               // the earlier run's output folder (empty: no restart)
  std::optional<int> from_step;  // the step to continue after (none: the last one written)
  int stop_after_step = 0;       // > 0: stop once this many steps are done
};

// The options beside the case file that change a run's result, one
// "name=value" a line: refine, degree (the bodies' too), the solver, its
// options, its preconditioner and the process count, as `spec` holds them
// after the command line's overrides.  Written into every state file; a
// restart with another refine or degree is refused (the solver's may change).
std::string run_options(const CaseSpec& spec);

// The earlier run a restart continues: the folder its state files are in,
// whether that is a stopped run's staging folder, its steps 1..N, and the
// steps 0..N of its solution.pvd (none without one, or with [output] vtk = false).
struct EarlierRun {
  std::string folder;
  bool stopped = false;
  std::vector<StepState> steps;
  std::vector<VtkStep> vtk_steps;
};

// Finds and checks the earlier run of o.dir (above), writing nothing: its
// state files were written from the same case file (the hash of spec.path)
// with the same discretisation `options` (run_options: refine, degree), are whole (their checksums), and
// are steps of the case's schedule (their times and next increments); its
// solution.pvd names only ParaView files of its own folder.  Throws
// InputError in one line naming the file and what differs or is wrong.
EarlierRun read_earlier_run(const CaseSpec& spec, const std::string& options, const RestartOptions& o);

// Takes the earlier run's files of its steps (the state files and, with
// `vtk`, the .vtu of its .pvd's steps) into `staging` (hard links, copies
// where the file system has none); returns the .pvd's steps.
std::vector<VtkStep> adopt_earlier_steps(const EarlierRun& run, const std::string& staging, bool vtk);

}  // namespace igac
