// SPDX-License-Identifier: BSD-3-Clause
// Part of a side, [faces.NAME] side = "...", range = [from, to]: the patch
// is cut where the range ends (engine/geometry/patch_partition.hpp) and the
// name stands for the sides of the pieces within the range.  Every face,
// name and interface of the body is carried over to the pieces, so a
// contact, a pressure (with or without a fluid), a traction or a support on
// the part is posed as on a whole side, in both kinematics, with friction,
// against obstacles and bodies, on both solvers.
#pragma once

#include <vector>

#include "model/model.hpp"

namespace igac {

// Cuts this body's refined patches (`own`, local numbers; `interfaces` in
// them) for the case's partial faces that lie on it, renumbers the body's
// named faces into pieces and names each part (m.faces).  `offset` is the
// body's first patch in the model, `file_patches` how many patches its shape
// or file has.  Throws InputError naming the case's key for a side that is
// several sides, a name taken, or a cut the body's interfaces do not allow.
void cut_partial_faces(Model& m, const BodySpec& body, int offset, int file_patches, std::vector<NurbsPatch>& own,
                       std::vector<PatchInterface>& interfaces);

// A side as the file names it ("1:west"): a reoriented patch runs its first
// direction backwards, so its u sides swap names.
PatchSide side_in_file(const Model& m, PatchSide s);

// A partial face no body has: its side names no side of any body.
void check_partial_faces_found(const Model& m);

// The sides of the model that make up side `s` of a patch as the shape or
// the file gives it (the pieces' sides, when the patch was cut).
std::vector<PatchSide> sides_of_pieces(const Model& m, const PatchSide& s);

}  // namespace igac
