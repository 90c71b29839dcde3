// SPDX-License-Identifier: BSD-3-Clause
// Splitting a NURBS patch in two along a parametric direction, and affine
// reparametrisation of a patch to the unit cube.
//
// Splitting (Piegl & Tiller, The NURBS Book, 5.3 "curve splitting"): insert
// the split value s into direction d until its multiplicity is degree + 1
// (A5.4 through insert_knots in refinement.hpp).  The knot vector then falls
// apart into [.., s^(p+1)] and [s^(p+1), ..]: the basis functions left of s
// vanish on the right and vice versa, so the first k control points (k = the
// index of the first copy of s) describe the left half and the others the
// right half.  Both halves keep the original parameters (the left half lives
// on [a, s], the right on [s, b]), so each evaluates exactly like the
// original on its range.  Knot insertion never changes the geometry.
//
// Reparametrisation u -> (u - a) / (b - a) changes only the knot values, not
// the control points or weights: the curve is the same, at new parameters.
#pragma once

#include <utility>

#include "engine/spline/nurbs_patch.hpp"

namespace igac {

// The two halves (first: parameters below `value`, second: above) of `patch`
// cut at `value` in direction `direction`.  Throws SplineError when the
// direction does not exist or the value does not lie strictly inside the
// parameter range.
std::pair<NurbsPatch, NurbsPatch> split_patch(const NurbsPatch& patch, int direction, double value);

// The same patch with every direction's parameter range mapped affinely to
// [0, 1] (the range the engine's refinement targets use).
NurbsPatch normalised(const NurbsPatch& patch);
// The same patch with parametric direction `direction` run backwards
// (u -> first + last - u): the same geometry, the opposite orientation.
NurbsPatch reversed(const NurbsPatch& patch, int direction);

}  // namespace igac
