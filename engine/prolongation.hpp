// SPDX-License-Identifier: BSD-3-Clause
// The prolongation between two nested discretisations of the same body:
// the fine mesh's knot vectors contain the coarse ones (patch by patch,
// direction by direction: `igac run --refine r` contains `--refine r-1`), so
// every coarse displacement is exactly a fine one.  Knot insertion gives its
// coefficients (Piegl & Tiller A5.4 on homogeneous coordinates):
//
//     u_fine = W_f^-1 (T_u x T_v x T_w) W_c u_coarse        (per component)
//
// with T_d the 1D knot-insertion matrices (engine/spline/refinement) and
// W the control-point weights.  Assembled over the body's control points
// (a point shared by two patches on an interface gets its row once: both
// patches give the same one, the interface being conforming) and restricted
// to the free equations of both DofMaps: a prescribed coarse dof is dropped
// (a correction vanishes there), a prescribed fine dof has no row.  Geometric
// multigrid's interpolation (solvers/petsc_multigrid).
#pragma once

#include <Eigen/SparseCore>

#include "engine/assembly.hpp"
#include "engine/body.hpp"

namespace igac {

// P (fine.num_free() x coarse.num_free()), rows in the fine DofMap's
// equation numbering, columns in the coarse one's.  Throws SplineError when
// the bodies are not nested (different patch counts, degrees, or a coarse
// knot missing from the fine knot vector).
Eigen::SparseMatrix<double, Eigen::RowMajor> prolongation(const Body& coarse, const DofMap& coarse_dofs,
                                                          const Body& fine, const DofMap& fine_dofs);

}  // namespace igac
