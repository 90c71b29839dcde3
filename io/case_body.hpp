// The body a case describes, as it is described: the coarse multi-patch
// geometry before degree elevation and knot refinement (what `igac geometry`
// writes, engine/geometry/multipatch.hpp).  Today a built-in shape
// (engine/geometry/shapes.hpp) as one patch with every side on the boundary.
#pragma once

#include "engine/geometry/multipatch.hpp"
#include "io/case_file.hpp"

namespace igac {

// Throws InputError (naming the case file) when the shape's data are invalid.
MultiPatch case_body(const CaseSpec& spec);

}  // namespace igac
