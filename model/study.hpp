// SPDX-License-Identifier: BSD-3-Clause
// Refinement studies on nested meshes: the case solved at refine = r0, r0+1,
// ..., each level halving every knot span, each level's contact iteration
// started from the level below.  Errors are taken against the closed-form
// solution when the case's reference has one (Lame), else against the
// finest level, and only for levels with h >= 4 h_ref (docs/design.md,
// "Refinement studies").  Contact cases add the pressure error against
// Hertz and against the reference.  Rates between consecutive reported
// levels: log(e_l / e_{l+1}) / log(h_l / h_{l+1}).
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "model/run_result.hpp"

namespace igac {

struct StudyResult {
  std::vector<Model> models;       // per level
  std::vector<RunResult> results;  // per level
  bool exact = false;              // errors against a closed form (else against the finest level)
  std::vector<int> reported;       // the levels whose errors are taken
  // Per level (filled for reported levels): error name -> value.
  std::vector<std::map<std::string, double>> errors;
  // Per error name: the rate between reported[i] and reported[i + 1] (may be
  // non-finite, e.g. for a zero error).
  std::map<std::string, std::vector<double>> rates;
};

// Sees each level once it is solved.
using LevelObserver = std::function<void(int level, const Model&, const RunResult&)>;

// Throws InputError for too few levels or a finest level too large, and
// std::runtime_error when a level does not converge.
StudyResult solve_study(CaseSpec spec, int levels, bool quiet, const LevelObserver& on_level = {});

}  // namespace igac
