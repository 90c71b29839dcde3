// SPDX-License-Identifier: BSD-3-Clause
// Multi-patch geometry as it is described (before any refinement): the
// patches, the sides they share, and the sides on the boundary.  This is the
// contract between the geometry file reader/writer (io/gismo_xml) and the
// engine, which joins the patches C0 across conforming interfaces.
//
// Sides follow G+Smo's numbering (gsBoundary.h): 1 west u = 0, 2 east u = 1,
// 3 south v = 0, 4 north v = 1, 5 front w = 0, 6 back w = 1; igac's Face is
// (direction, at_end), so side s is Face{(s - 1) / 2, (s - 1) % 2 == 1}.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "engine/spline/nurbs_patch.hpp"

namespace igac {

// One side (face) of one patch.
struct PatchSide {
  int patch = 0;
  Face face;
  PatchSide() = default;
  PatchSide(int patch_index, Face f) : patch(patch_index), face(f) {}
  // A face of a one-patch body (patch 0).
  PatchSide(Face f) : face(f) {}  // NOLINT: implicit on purpose
  bool operator==(const PatchSide& o) const { return patch == o.patch && face == o.face; }
};

// Two patch sides that coincide.  The orientation is not stored: the engine
// matches the sides' control points geometrically after refinement, which
// also covers flipped and permuted parametrisations.
struct PatchInterface {
  PatchSide first, second;
};

struct MultiPatch {
  std::vector<NurbsPatch> patches;
  std::vector<PatchInterface> interfaces;
  std::vector<PatchSide> boundary;  // may be empty (then: every side not in an interface)
};

// G+Smo side number (1..6) <-> Face.
inline Face face_of_gismo_side(int side) { return Face{(side - 1) / 2, (side - 1) % 2 == 1}; }
inline int gismo_side_of(const Face& f) { return 2 * f.direction + (f.at_end ? 2 : 1); }
// "west", "east", "south", "north", "front", "back" for sides 1..6.
inline const char* gismo_side_name(int side) {
  static const char* names[] = {"west", "east", "south", "north", "front", "back"};
  return side >= 1 && side <= 6 ? names[side - 1] : "?";
}

// The patch directions along a face (all but its normal one), ascending:
// the directions of NurbsPatch::face_patch.
inline std::vector<int> face_directions(int param_dim, const Face& f) {
  std::vector<int> t;
  for (int d = 0; d < param_dim; ++d)
    if (d != f.direction) t.push_back(d);
  return t;
}

// A corner of side `f` of patch `p`: its control point (open knot vectors
// interpolate there); bits[k] picks the end of face direction k.
inline Eigen::VectorXd face_corner(const NurbsPatch& p, const Face& f, const std::vector<int>& bits) {
  std::array<int, 3> idx{0, 0, 0};
  int k = 0;
  for (int d = 0; d < p.param_dim(); ++d)
    idx[d] = d == f.direction ? (f.at_end ? p.num_basis(d) - 1 : 0) : (bits[k++] ? p.num_basis(d) - 1 : 0);
  return p.points().row(p.index(idx)).transpose();
}

// "1:west": a side as case files name it.
inline std::string side_label(const PatchSide& s) {
  return std::to_string(s.patch) + ":" + gismo_side_name(gismo_side_of(s.face));
}

// One patch as a body: every side on the boundary.
inline MultiPatch single_patch_body(const NurbsPatch& patch) {
  MultiPatch body;
  body.patches = {patch};
  for (int s = 1; s <= 2 * patch.param_dim(); ++s) body.boundary.push_back(PatchSide{0, face_of_gismo_side(s)});
  return body;
}

}  // namespace igac
