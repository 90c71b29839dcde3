// SPDX-License-Identifier: BSD-3-Clause
// What a case will cost before anything is built: the peak memory of a
// small-deformation run, and the check that the mesh asked for fits.
#pragma once

#include <optional>

#include "model/case_spec.hpp"

namespace igac {

// The mesh build_model will make, counted from the coarse patches without
// building it: every patch's own breakpoints united with the requested
// ones after refine (elements, and control points summed over the patches).
struct MeshCount {
  double elements = 0, control_points = 0;
};
MeshCount estimated_mesh(const CaseSpec& spec);
// The peak memory a small-deformation run of this case is expected to need
// (bytes), on spec.solver.processes processes: what apply_overrides
// compares with the machine's memory.
double estimated_peak_bytes(const CaseSpec& spec);
// This machine's physical memory (bytes): what a run's estimate must fit in.
double physical_memory_bytes();
// Applies a --degree / --refine override, checks it, and checks the memory
// the mesh would need; throws InputError naming the option.
void apply_overrides(CaseSpec& spec, std::optional<int> degree, std::optional<int> refine);

}  // namespace igac
