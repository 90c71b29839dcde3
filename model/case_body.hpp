// SPDX-License-Identifier: BSD-3-Clause
// The bodies a case describes, as it describes them: the coarse multi-patch
// geometry before degree elevation and knot refinement (what `igac geometry`
// writes, engine/geometry/multipatch.hpp): the patches a geometry file held
// when the case was read, or a built-in shape (engine/geometry/shapes.hpp) as
// one patch with every side on the boundary.
#pragma once

#include "engine/geometry/multipatch.hpp"
#include "engine/geometry/shapes.hpp"
#include "model/case_spec.hpp"

namespace igac {

// One body's coarse patches.  Throws InputError (naming the case file) when
// the shape's data are invalid.
MultiPatch body_patches(const CaseSpec& spec, const BodySpec& body);
// A built-in shape as the engine's coarse Geometry (before degree elevation
// and refinement), with its face names.  Throws InputError for a body that
// reads a geometry file (its patches come from body_patches).
Geometry body_geometry(const CaseSpec& spec, const BodySpec& body);
// Every body of the case, its patches one after another (body by body, in
// the order of the case's [[body]] tables); no interface joins two bodies.
MultiPatch case_body(const CaseSpec& spec);

}  // namespace igac
