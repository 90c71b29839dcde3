// SPDX-License-Identifier: BSD-3-Clause
// Exact coarse NURBS geometries (one patch each), with their boundary faces
// named for people.  Circles are rational quadratics (Piegl & Tiller 7.5), so
// refinement keeps them exact.  Every shape also answers to the parametric
// face names u0, u1, v0, v1 (, w0, w1).
//
// quarter_disc(R): x >= 0, y in [-R, 0], the 2D Hertz model (paper, 4.1).
//   v = 0 is the whole arc from the bottom point A = (0, -R) (u = 0) to
//   B = (R, 0) (u = 1): the contact face, with A at a regular corner.
//   u = 1 is the top edge y = 0 (from B to the centre).  The x = 0 edge is
//   covered by u = 0 (from A up to D = (0, -R/2)) and v = 1 (from D to the
//   centre).  A single quadrilateral patch of a three-cornered region needs
//   one corner where the boundary is straight: it is D, on the symmetry line
//   half a radius away from the contact zone; det J > 0 everywhere else.
// sphere_octant(R): x, y >= 0, z in [-R, 0], the 3D Hertz model (paper, 4.2):
//   the quarter disc (in the plane y = 0) revolved about the x axis.  v = 0 is
//   the spherical contact face with the contact point (0, 0, -R) at its
//   regular corner u = 0, w = 1.  Faces: top (z = 0, w = 0), back (y = 0,
//   w = 1), left (x = 0: u = 0 and v = 1), and u = 1, which collapses onto the
//   x axis (y = z = 0), far from the contact zone; coincident control points
//   there share their unknowns (DofMap).
// quarter_annulus(a, b): a <= r <= b, x, y >= 0; u radial, v along the angle
//   from the x axis.  Faces: inner, outer, bottom (y = 0), left (x = 0).
// rectangle(Lx, Ly) = [0, Lx] x [0, Ly]: left, right, bottom, top.
// box(Lx, Ly, Lz): left/right (x), front/back (y), bottom/top (z).
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string_view>
#include <string>
#include <vector>

#include "engine/geometry/multipatch.hpp"
#include "engine/spline/nurbs_patch.hpp"

namespace igac {

struct Geometry {
  NurbsPatch patch;
  std::map<std::string, std::vector<PatchSide>> faces;  // named boundary parts (sides of patch 0)
};

Geometry quarter_disc(double radius);
Geometry sphere_octant(double radius);
Geometry quarter_annulus(double inner_radius, double outer_radius);
Geometry rectangle(double lx, double ly);
Geometry box(double lx, double ly, double lz);

// The built-in shapes behind a registry: each declares its case-file keys
// (a number, or a vector of `length` numbers, all positive lengths) and makes
// its Geometry from them.  A new shape is one file in engine/geometry/shapes/
// and one line in shapes.cpp.
using ShapeValues = std::map<std::string, std::vector<double>, std::less<>>;
struct ShapeKey {
  std::string_view key, meaning;
  int length = 1;  // 1: one number; else a vector of that many
};
struct ShapeType {
  std::string_view name, description;
  int dim = 2;
  bool curved = false;  // exact arcs: quadratic NURBS, degree >= 2
  std::span<const ShapeKey> keys;
  Geometry (*make)(const ShapeValues& values);  // throws SplineError for invalid values
};
std::span<const ShapeType* const> shape_types();
const ShapeType* find_shape_type(std::string_view name);
const ShapeType& quarter_disc_shape();
const ShapeType& sphere_octant_shape();
const ShapeType& quarter_annulus_shape();
const ShapeType& rectangle_shape();
const ShapeType& box_shape();

// The faces a name stands for on this geometry (named or parametric), or
// nothing when the name is unknown.
std::optional<std::vector<PatchSide>> find_faces(const Geometry& g, const std::string& name);
// All accepted face names, for error messages.
std::vector<std::string> face_names(const Geometry& g);

}  // namespace igac
