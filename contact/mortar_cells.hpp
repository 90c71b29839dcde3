// SPDX-License-Identifier: BSD-3-Clause
// Segmented mortar integration on a 3D slave face (Puso and Laursen 2004;
// Popp, Gee and Wall 2009, "segment-based integration"): each slave element
// is cut into cells, the parts of it whose points project into one master
// element, so that the master's basis is smooth on every cell and the
// contact patch test between non-matching meshes holds to round-off.
//
// The cut, in slave element e's Bezier coordinates s in [0, 1]^2: the
// projection P(s) (the master side and parameters eta of the master point
// nearest to e's point at s, MasterSurface::project, the same projection
// as the integrand's) is sampled at the corners of the element's two
// triangles; where it is affine on a triangle (checked at the edges'
// midpoints to kAffineTolerance of the master element's size) the triangle
// is split along the lines eta_d = beta of every master breakpoint beta it
// spans (a convex polygon cut by a line stays convex, the eta of a new
// vertex interpolated along its edge); otherwise the triangle is halved
// into 4, at most kMaxDepth times (curved faces: the cuts are then the
// affine approximation's, their error that of the polyline of 2^kMaxDepth
// pieces per element edge).  On flat affine faces P is affine and the cuts
// exact.  Each cell is split in triangles (a fan) that get a collapsed
// Gauss rule of the degree of the mortar integrands on flat faces
// (engine/quadrature.hpp, triangle_gauss_rule); the cells of halved
// triangles (curved faces, where no rule is exact) the 2 x 2 rule.
//
// Degenerate cases: an element whose points (a 5 x 5 grid) all project
// into one master element is integrated with its own tensor Gauss rule
// (the element-based points), and a triangle whose corners and edge
// midpoints all do is one cell; a cell below kSliver of the element (a
// master edge through a slave corner) is dropped; slave points beyond the
// master's edge project on it (the closest point), and their triangles are
// cut where that projection crosses a breakpoint; a triangle whose corners
// project on different master sides after kMaxDepth halvings is one cell.
#pragma once

#include <Eigen/Dense>
#include <limits>
#include <vector>

#include "contact/master_surface.hpp"
#include "contact/weighted_gap.hpp"
#include "engine/spline/bezier_extraction.hpp"

namespace igac {

using ParamPolygon = std::vector<Eigen::Vector2d>;

// Signed area of a polygon (counter-clockwise positive).
double polygon_area(const ParamPolygon& poly);

// One cell of a slave element: a convex polygon (its Bezier coordinates,
// counter-clockwise) whose points project into one element of master side `side`.
struct MortarCell {
  int side = 0;
  ParamPolygon polygon;
  int depth = 0;  // halvings of its triangle: > 0 on curved faces only
};

// The cells of element e of `slave` (a slave face side's Bezier mesh at its
// current position) against `master` as it stands; false (no cells) when
// the element lies in one master element, or when all its sample points
// lie farther from the master than `far` times the element's diameter: it
// is then integrated whole.
bool mortar_cells(const BezierMesh& slave, int e, const MasterSurface& master, std::vector<MortarCell>& cells,
                  double far = std::numeric_limits<double>::infinity());

// The quadrature of segmented integration on one side of a 3D slave face:
// points in the side's face-patch parameters and their weights (parameter
// area, without the surface Jacobian).  `u_side`: the displacement of the
// side's control points (its face numbering; null: none), the cut taken at
// the current position.  `points`: the element-based rule's Gauss points per
// direction (for uncut elements).  At a current position (u_side given: large
// deformation, the rule made again for each state) an element farther from
// the master than its diameter is not cut: it is not in contact in this
// state, and the element rule integrates its share of its multipliers'
// weighted gaps and of G to the accuracy of element-based integration (at
// a converged state the elements of active multipliers touch, and are cut;
// measured: docs/benchmarks.md, "The two-body Newton iteration").  In the reference
// position (small deformation: one rule for the whole solve, whatever the
// body's motion) every element is cut.
void segmented_side_rule(const ContactSide& side, const Eigen::MatrixXd* u_side, const MasterSurface& master,
                         int points, std::vector<Eigen::VectorXd>& xi, std::vector<double>& weights);

}  // namespace igac
