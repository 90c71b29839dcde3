// SPDX-License-Identifier: BSD-3-Clause
// The Newton matrix of a problem with constraints, in blocks: what a problem
// hands to the load-stepping driver (engine/load_stepping.hpp) and the driver
// to its linear backend (engine/linear_backend.hpp).
//
//   J = [ K            B^T     ]   K: n x n (symmetric pattern), B: m x n,
//       [ diag(s) B    diag(d) ]   and per constraint row k either s_k = 0
//                                  (inactive: d_k dl_k = b_k) or d_k = 0
//                                  (active: s_k B_k du = b_k).
//
// This is the semismooth-Newton matrix of weighted-gap contact
// (model/finite_strain_problem.hpp): B holds the gap derivatives, s the scale c of
// the active rows, d the weights of the inactive ones.  Element-local
// unknowns (the mixed formulation's dilatations) come condensed (Local).
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <vector>

namespace igac {

struct BlockJacobian {
  Eigen::SparseMatrix<double> K;  // a factorisation uses (K + K^T) / 2
  // Optional: a part of the displacement block beside K, so that J's is
  // K + K_coupling (empty: none).  A factorisation leaves it out and GMRES
  // applies it: the follower pressures' load stiffness (unsymmetric, on the
  // loaded faces' pattern; engine/follower_pressure.hpp) and the
  // large-deformation mortar contact's curvature terms that couple two
  // bodies' control points (contact/finite_strain_mortar.hpp), which no
  // element of either body joins.  Its pattern may change every call.
  Eigen::SparseMatrix<double> K_coupling;
  // K is the whole Newton matrix (B empty), unsymmetric beyond what GMRES
  // absorbs: factorised by UMFPACK as it stands (large-deformation friction,
  // contact/finite_strain_friction.hpp, whose slip rows tie the tangential
  // multipliers to the normal ones).
  bool general = false;
  Eigen::SparseMatrix<double, Eigen::RowMajor> B;  // m x n (m = 0: no constraints)
  Eigen::VectorXd s, d;                            // m each
  // Motions the constraints must hold (K R = 0 up to the terms GMRES
  // absorbs; n x k, orthonormal) and k equations where they are pinned.
  Eigen::MatrixXd rigid_modes;
  std::vector<int> pinned;
  // Optional: element-local unknowns z, the last C.rows() entries of x
  // (after the multipliers), condensed in the solve: the mixed
  // formulation's block dilatations (u-p Newton, engine/volumetric_projection.hpp).
  // Their rows read h (C du - dz) and the displacement rows gain
  // C^T diag(g) dz, so dz = C du - b_z / h and what is left is
  //   (K_uu + C^T diag(g) C) du + ... = b_u + C^T diag(g) b_z / h:
  // K above is that condensed matrix (the pattern and symmetry of K_uu),
  // the whole J has K - C^T diag(g) C in its displacement block.
  // C: z x n_u, n_u the displacements, the first n_u entries of x.
  struct Local {
    Eigen::SparseMatrix<double, Eigen::RowMajor> C;
    Eigen::VectorXd g, h;
    int size() const { return int(C.rows()); }
  } local;
};

// J as one sparse matrix, the local unknowns included (the tests').
Eigen::SparseMatrix<double> assemble_full(const BlockJacobian& J);


// J without the local unknowns (Local condensed): n + m rows, K + K_coupling
// in the displacement block, the constraint rows and columns.
Eigen::SparseMatrix<double> assemble_condensed(const BlockJacobian& J);

// Rows [begin, end) of assemble_condensed(J) + `extra` (when given: a
// matrix of the condensed J's size, e.g. an augmented Lagrangian's
// B^T W B), in its first `columns` columns (-1: all), as a matrix of
// end - begin rows: what one process hands to a distributed solver, built
// without a copy of the whole (K is read in place).  Entries of the pattern
// whose value is zero are kept (the pattern stays as the values change);
// the columns of each row increase.
Eigen::SparseMatrix<double, Eigen::RowMajor> condensed_rows(
    const BlockJacobian& J, int begin, int end, int columns = -1,
    const Eigen::SparseMatrix<double, Eigen::RowMajor>* extra = nullptr);

// A right-hand side b of the whole J (local unknowns last) condensed to
// assemble_condensed's rows: b_u += C^T diag(g) b_z / h; and the local part
// of the solution recovered from the condensed one: dz = C du - b_z / h.
struct CondensedRhs {
  Eigen::VectorXd b;     // n + m entries
  Eigen::VectorXd bz_h;  // b_z / h (empty without local unknowns)
};
CondensedRhs condense_rhs(const BlockJacobian& J, const Eigen::VectorXd& b_whole);
// x: the condensed solution (n + m entries) on entry, the whole one on return.
void recover_local(const BlockJacobian& J, const CondensedRhs& rhs, Eigen::VectorXd& x);

}  // namespace igac
