// Refinement studies on nested meshes (`igac study`): the case is solved at
// refine = r0, r0+1, ..., each level halving every knot span.  Errors are
// taken against the closed-form solution when the case has one (Lame), else
// against the finest level, and only for levels with h >= 4 h_ref (paper,
// section 4.1).  Contact cases add the pressure error against Hertz and
// against the reference.  Rates between consecutive levels:
// log(e_l / e_{l+1}) / log(h_l / h_{l+1}).
#pragma once

#include <optional>
#include <string>

#include "io/case_file.hpp"

namespace igac {

struct StudyOptions {
  int levels = 4;
  std::string out;  // empty: no files
  bool quiet = false;
};

// Returns the process exit code.
int run_study(CaseSpec spec, const StudyOptions& options);

}  // namespace igac
