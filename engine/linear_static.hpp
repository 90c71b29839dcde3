// SPDX-License-Identifier: BSD-3-Clause
// What a small-deformation solve needs besides the matrix: the rigid motions
// that the Dirichlet conditions leave free (a body held only by contact has
// them), and a choice of dofs to pin them while K is factorised.
//
// Rigid motions are exact in the NURBS space (partition of unity and affine
// invariance: translations u_A = t, rotations u_A = W X_A), so the candidate
// modes are known in closed form; those that vanish on every prescribed dof
// survive (null space of the prescribed rows, by SVD).  An axisymmetric body
// has one rigid motion, the translation along its axis.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "engine/assembly.hpp"

namespace igac {

struct RigidModes {
  Eigen::MatrixXd modes;     // n_free x k, columns orthonormal (k may be 0)
  std::vector<int> pinned;   // k free equations where the modes are best conditioned
};

// Each separate body (Body::parts) has its own rigid motions.
RigidModes free_rigid_modes(const Body& body, const DofMap& dofs);

// K with the pinned equations replaced by identity rows and columns (SPD
// when the only singularity of K is the rigid modes).
Eigen::SparseMatrix<double> pin_equations(const Eigen::SparseMatrix<double>& K, const std::vector<int>& pinned);

}  // namespace igac
