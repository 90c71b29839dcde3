// SPDX-License-Identifier: BSD-3-Clause
// The start of the active-set iteration on a refined mesh from the converged
// solution one mesh coarser (nested iteration).  Started from the closed
// initial gaps, the iteration overshoots and then shrinks the set a little
// per solve; from the coarse solution it only settles the rim of the
// contact zone (measured: docs/petsc.md, "Nested iteration").
//
// The coarse displacement is exactly a fine one (engine/prolongation: u_f =
// P u_c); the coarse multipliers are a field on the same contact sides,
// evaluated at the fine multipliers' anchors (for p = 2 the constants of
// the coarse face element holding the fine one).  The first active set is
// the usual rule on these: lambda_K + c_n (Pi g)_K < 0 (contact/small_strain_contact).
#pragma once

#include <Eigen/SparseCore>
#include <vector>

#include "contact/small_strain_contact.hpp"
#include "contact/weighted_gap.hpp"

namespace igac {

struct ActiveSetStart {
  std::vector<char> active;  // per fine multiplier
  Eigen::VectorXd u;         // fine free displacements
  Eigen::VectorXd lambda;    // per fine multiplier, zero where inactive
};

// The coarse multipliers as fine ones: the coarse field sum_j lambda_j B^c_j
// at the fine multipliers' anchors (Greville points).  Exact for p = 2 and
// 3 (a piecewise constant at points inside the fine elements; a continuous
// piecewise linear at its breakpoints), an interpolation beyond.
// coarse_faces / fine_faces as below.
Eigen::VectorXd prolongated_multipliers(const std::vector<const ContactFace*>& coarse_faces,
                                        const std::vector<const ContactFace*>& fine_faces,
                                        const Eigen::VectorXd& coarse_lambda);

// coarse_faces / fine_faces: the contact faces of the two meshes in the
// order their multipliers are stacked (the same sides, the fine knot vectors
// containing the coarse ones); P: fine free x coarse free; fine_op the fine
// weighted gaps; k the free rigid motions; cn the complementarity scale.
ActiveSetStart start_from_coarse(const std::vector<const ContactFace*>& coarse_faces,
                                 const std::vector<const ContactFace*>& fine_faces,
                                 const Eigen::SparseMatrix<double, Eigen::RowMajor>& P, const ContactSolution& coarse,
                                 const WeightedGapOperator& fine_op, int k, double cn);

}  // namespace igac
