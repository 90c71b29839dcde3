// SPDX-License-Identifier: BSD-3-Clause
// Warnings for a motion the small-deformation solve barely holds (a
// near-mechanism): the result along it is large and not to be trusted, and
// nothing else says so (a plate that can rotate about its contact gave a
// tangential force of about 0 without a word).  Two places can nearly lose
// a motion:
//  - the stiffness K: its factor's pivots d_i = L_ii^2 against K_ii.  A
//    ratio K_ii / d_i above kMaxPivotRatio (MSC Nastran's MAXRATIO
//    default, 1e7) means that once every other unknown is eliminated that
//    one keeps almost none of its stiffness: K is nearly singular along a
//    motion that moves it (a body hinged on a tiny face, a thin neck);
//  - the contact, for the rigid motions no Dirichlet condition holds:
//    B = [G_A; T_S] R, the active multipliers' weighted gaps (and the stuck
//    ones' tangential slips) of each rigid motion (R: the orthonormal free
//    rigid modes).  A combination B c smaller than
//    1 / sqrt(kMaxPivotRatio) of the best held one (the same ratio for
//    B^T B) is barely held: a load along it needs huge contact forces, or
//    moves the body far (a body rolling on a nearly circular face).
// The motion is named: the rigid motion nearest to it (a rotation about a
// point in 2D, about an axis in 3D, or a translation), else where it moves
// the body most.  Independent of the solver's condition estimate: these
// name the motion, that one measures the matrix.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "contact/small_strain_contact.hpp"
#include "engine/cholesky.hpp"
#include "engine/linear_static.hpp"
#include "model/model.hpp"

namespace igac {

inline constexpr double kMaxPivotRatio = 1e7;

// The motion u (n_cp x dim, the body's control points) in words: "a
// rotation about (x, y)", "a rotation about the axis (a, b, c) through
// (x, y, z)", "a translation along (a, b)" when it is mostly rigid on the
// part of the body it moves most, else "a deformation largest at (x, y)".
std::string describe_motion(const Body& body, const Eigen::MatrixXd& u);

// The warning for K, factorised in `chol` with the equations `pinned`
// replaced by identity rows (excluded), or nothing.
std::optional<std::string> stiffness_warning(const Model& m, const Eigen::SparseMatrix<double>& K,
                                             const std::vector<int>& pinned, const SparseCholesky& chol);

// The warning for the rigid motions the contact holds at the solution `s`
// of operator `op`, or nothing.
std::optional<std::string> contact_hold_warning(const Model& m, const WeightedGapOperator& op,
                                                const ContactSolution& s, const RigidModes& modes);

}  // namespace igac
