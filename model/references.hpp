// SPDX-License-Identifier: BSD-3-Clause
// Reference solutions a case can be compared with ([reference] solution =
// NAME): a small registry.  Each entry says which cases it fits and adds to
// a run's result its errors against the closed form: Hertz (a round body on
// a rigid plane: half width, peak pressure, the pressure's L2 error) and
// Lame (the thick cylinder under internal pressure: displacement L2 and H1
// errors).  A new reference is one more entry in references.cpp.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/error_norms.hpp"
#include "model/model.hpp"
#include "model/run_result.hpp"

namespace igac {

struct ReferenceSolution {
  std::string_view name;
  // Why `spec` cannot be compared with it ("" when it can): checked when the
  // case is read, before anything is built.
  std::string (*unusable)(const CaseSpec& spec);
  // The closed-form displacement, for references that have one.
  std::optional<ExactDisplacement> (*displacement)(const CaseSpec& spec);
  // The closed-form contact pressure, for references that have one.
  std::optional<HertzSolution> (*contact_pressure)(const CaseSpec& spec);
};

// The entry named `name` ("none" and unknown names: null).
const ReferenceSolution* find_reference(std::string_view name);
// Every registered name, for error messages ("none" included).
std::vector<std::string_view> reference_names();
// The case's closed-form displacement, if its reference has one.
std::optional<ExactDisplacement> exact_displacement(const CaseSpec& spec);
// Adds to `r` what the case's reference compares: the Hertz values and the
// pressure error of the first contact (when the run has a contact result),
// the displacement errors (small deformation, where the closed form holds).
void compare_with_reference(const Model& m, RunResult& r);

}  // namespace igac
