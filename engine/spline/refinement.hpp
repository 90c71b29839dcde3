// SPDX-License-Identifier: BSD-3-Clause
// Exact refinement of a NURBS patch and of fields carried on it.
//
// Both operations act on homogeneous coefficients (w P, w, w u): the
// rational patch is the projection of a polynomial spline in one dimension
// more, and that spline is refined exactly.
//  - h-refinement: knot insertion, Piegl & Tiller A5.4 (RefineKnotVectCurve)
//    applied along one parametric direction.
//  - p-refinement: degree elevation.  The elevated space (every breakpoint's
//    multiplicity raised with the degree) contains the old one, so
//    interpolation at the new Greville abscissae (unisolvent by
//    Schoenberg-Whitney) reproduces the old spline exactly; the banded
//    collocation system is solved by sparse LU.
// Fields are matrices with one row per control point (e.g. a displacement);
// they are refined with the patch so that they describe the same function.
#pragma once

#include <Eigen/SparseCore>
#include <vector>

#include "engine/spline/nurbs_patch.hpp"

namespace igac {

struct RefinedPatch {
  NurbsPatch patch;
  std::vector<Eigen::MatrixXd> fields;
};

// Inserts the sorted knots `new_knots` into direction `direction`.
RefinedPatch insert_knots(const NurbsPatch& patch, int direction,
                          const std::vector<double>& new_knots,
                          const std::vector<Eigen::MatrixXd>& fields = {});
// Raises the degree of direction `direction` by `by`.
RefinedPatch elevate_degree(const NurbsPatch& patch, int direction, int by,
                            const std::vector<Eigen::MatrixXd>& fields = {});

// Convenience: raise every direction to `degree` (never lowers), then split
// every span into `parts` (h-refinement after p-refinement: k-refinement).
NurbsPatch elevate_to(const NurbsPatch& patch, int degree);
NurbsPatch subdivide(const NurbsPatch& patch, int parts);
// Refine direction d to the given finer knot vector (same degree).
NurbsPatch refine_to(const NurbsPatch& patch, int direction, const KnotVector& finer);

// The knot-insertion matrix T (fine.num_basis() x coarse.num_basis()) of a
// B-spline space into a finer one of the same degree: a spline with
// coefficients c on `coarse` has coefficients T c on `fine` (the same A5.4
// applied to the identity; for NURBS it acts on homogeneous coefficients).
// Throws SplineError when `fine` does not contain `coarse`.
Eigen::SparseMatrix<double> knot_insertion_matrix(const KnotVector& coarse, const KnotVector& fine);

}  // namespace igac
