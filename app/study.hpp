// SPDX-License-Identifier: BSD-3-Clause
// `igac study`: a refinement study (model/study) printed as a table and
// written as study.json, study.csv and study.svg into the output folder.
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
