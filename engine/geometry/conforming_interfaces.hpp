// SPDX-License-Identifier: BSD-3-Clause
// Interfaces made conforming by knot insertion.  Each patch of a body is
// refined on its own ([mesh] elements and grading per patch, the file's own
// interior knots kept), so the two sides of an interface may end with
// different breakpoints: a patch with a knot the file put at u = 0.3, or a
// grading toward the start of a direction that runs the other way in the
// neighbour.  Inserting the missing knots on both sides (mapped through the
// interface's orientation: a reversed direction takes 1 - t) changes no
// geometry and makes both sides the same spline, so the body joins them C0.
// A knot inserted in one direction of a patch reaches its other interfaces
// along that direction; the insertion is repeated until nothing changes.
//
// Two sides whose parametrisations differ (the same curve, run at
// different speeds) stay non-conforming: the body then refuses the
// interface, naming both sides (engine/body.hpp).
#pragma once

#include <vector>

#include "engine/geometry/multipatch.hpp"

namespace igac {

struct InsertedKnots {
  int patch = 0, direction = 0, count = 0;
};

// Inserts into `patches` (parameter ranges [0, 1], one degree) the knots
// that make every interface conforming; returns how many knots went into
// which patch direction.
std::vector<InsertedKnots> make_interfaces_conform(std::vector<NurbsPatch>& patches,
                                                   const std::vector<PatchInterface>& interfaces);

}  // namespace igac
