// SPDX-License-Identifier: BSD-3-Clause
// Patches cut into pieces along parametric lines (planes in 3D), so that a
// part of a side becomes whole sides of pieces: a contact, a pressure or a
// support on part of a side is then posed as on any side, by every path of
// the engine, with nothing of its own.
//
// A cut at the fraction c of direction d inserts the parameter value there
// until its multiplicity is degree + 1 and takes the patch apart
// (engine/spline/split.hpp): no geometry changes, and the pieces, joined
// again across the cut, span the refined patch's space with the continuity
// across the cut lowered to C0 (as the knot of multiplicity p a CAD
// partition puts there).  A cut patch's first piece (every range starting at
// 0) keeps its number, the others are appended after the last patch.  Each
// piece is normalised to [0, 1]^d; its `box` says where it lies in the cut
// patch's parameters, as fractions.
//
// The interfaces follow: pieces of one patch are joined where they meet, and
// an interface of a cut side is replaced by the pairs of its pieces' sides
// that coincide (compared by their corner points).  A cut that crosses an
// interface into a patch that is not cut there leaves a side joined to part
// of another: cut_patches throws std::invalid_argument naming both.
#pragma once

#include <array>
#include <vector>

#include "engine/geometry/multipatch.hpp"

namespace igac {

// Where to cut one patch: fractions in (0, 1) of each parametric direction.
struct PatchCuts {
  int patch = 0;
  std::array<std::vector<double>, 3> at;
};

// One piece of a cut patch.
struct PatchPiece {
  int patch = 0;                                // its number among the patches
  std::array<std::array<double, 2>, 3> box{};  // its parameter range per direction, as fractions of the cut patch's
};

// Cuts the patches as `cuts` asks (a patch listed twice takes the union of
// its cuts; a fraction within 1e-13 of an existing knot is that knot).
// Returns, for each patch number before the cut, its pieces (one, the
// whole box, for a patch not cut); `interfaces` is rewritten in the new
// numbering.  Throws std::invalid_argument for a fraction outside (0, 1) or
// an interface the cut leaves unpaired.
std::vector<std::vector<PatchPiece>> cut_patches(std::vector<NurbsPatch>& patches,
                                                 std::vector<PatchInterface>& interfaces,
                                                 const std::vector<PatchCuts>& cuts);

// The pieces' sides that make up side `face` of the patch they were cut
// from, and those of them within `range` (one [from, to] fraction pair per
// direction along the side, in the order of face_directions).
std::vector<PatchSide> piece_sides(const std::vector<PatchPiece>& pieces, int param_dim, const Face& face);
std::vector<PatchSide> piece_sides_within(const std::vector<PatchPiece>& pieces, int param_dim, const Face& face,
                                          const std::vector<std::array<double, 2>>& range);

}  // namespace igac
