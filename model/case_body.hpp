// SPDX-License-Identifier: BSD-3-Clause
// The body a case describes, as it is described: the coarse multi-patch
// geometry before degree elevation and knot refinement (what `igac geometry`
// writes, engine/geometry/multipatch.hpp): the patches a geometry file held when the case was read,
// or a built-in shape (engine/geometry/shapes.hpp) as one patch with every
// side on the boundary.
#pragma once

#include "engine/geometry/multipatch.hpp"
#include "engine/geometry/shapes.hpp"
#include "model/case_spec.hpp"

namespace igac {

// Throws InputError (naming the case file) when the shape's data are invalid.
MultiPatch case_body(const CaseSpec& spec);
// A built-in shape as the engine's coarse Geometry (before degree elevation
// and refinement), with its face names.  Throws InputError for a case that
// reads a geometry file (its body comes from case_body).
Geometry case_geometry(const CaseSpec& spec);

}  // namespace igac
