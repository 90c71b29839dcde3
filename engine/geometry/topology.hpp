// SPDX-License-Identifier: BSD-3-Clause
// The topology of a multi-patch body found from its geometry: which patch
// sides coincide.  A geometry file may give no <interfaces> at all (a
// <MultiPatch> without topology, several <Geometry> and no <MultiPatch>), or
// describe a closed patch (a ring or a tube whose first and last control
// points coincide: its seam is two sides of one patch).  Left as they are,
// such sides are a slit in the body; joined, the body is what the file drew.
//
// Two sides coincide when their points agree, to the body's coincidence
// tolerance, at a 5 x 5 grid (5 points for the sides of a 2D patch) of their
// parameters under one of the orientations a side can have against another
// (each direction reversed or not, the two directions of a 3D side swapped
// or not).  Corners alone are not enough: two sides can share their corners
// and bulge apart in between; such pairs are returned separately, so the
// caller can say why they were left apart.  A side collapsed to a point (the
// pole of a disc) or, in 3D, to a curve (the axis of a cylinder) joins
// nothing: it has no area to share.
#pragma once

#include <vector>

#include "engine/geometry/multipatch.hpp"

namespace igac {

// The distance below which two points of the body count as one: 1e-9 of the
// diagonal of the control points' bounding box.  The same tolerance matches
// the control points of an interface (engine/body.hpp).
double coincidence_tolerance(const std::vector<NurbsPatch>& patches);

struct CoincidentSides {
  std::vector<PatchInterface> coincide;          // the same points under some orientation
  std::vector<PatchInterface> corners_only;      // the same corners, different points in between
};

// The pairs of `candidates` (sides of `patches`) that coincide.  Each side is
// in at most one pair; a pair may be two sides of one patch.
CoincidentSides find_coincident_sides(const std::vector<NurbsPatch>& patches, const std::vector<PatchSide>& candidates);

}  // namespace igac
