// SPDX-License-Identifier: BSD-3-Clause
// The Newton matrix of a problem with constraints, in blocks: what a problem
// hands to the load-stepping driver (engine/load_stepping.hpp) and the driver
// to its linear backend (engine/linear_backend.hpp).
//
//   J = [ K                  B^T              ]   K: n x n (symmetric
//       [ (diag(s) + M_B) B  diag(d) + M_l    ]   pattern), B: m x n
//
// This is the semismooth-Newton matrix of weighted-gap contact
// (model/finite_strain_problem.hpp): B holds the gap derivatives, s the scale c of
// the active rows, d the weights of the inactive ones: per constraint row k
// either s_k = 0 (inactive: d_k dl_k = b_k) or d_k = 0 (active:
// s_k B_k du = b_k).  M_B and M_l (m x m, sparse, usually empty) let a row
// combine several of B's rows and several multipliers: Coulomb friction's
// slip rows (contact/finite_strain_friction.hpp), whose tangential
// multipliers lean on their normal one and on its gap, B holding the
// tangential slips' rows below the gaps'.  A row is closed (solved with
// the displacements) when s_k != 0 or M_B or M_l holds an entry in it;
// otherwise it is d_k dl_k = b_k.  Element-local unknowns (the mixed
// formulation's dilatations) come condensed (Local).
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
  // absorbs: factorised by an LU as it stands (the small-deformation
  // frictional solve's last iterations, contact/small_strain_friction.cpp;
  // as_one_block below).
  bool general = false;
  Eigen::SparseMatrix<double, Eigen::RowMajor> B;  // m x n (m = 0: no constraints)
  Eigen::VectorXd s, d;                            // m each
  // m x m each, or empty (0 x 0): rows that combine (above)
  Eigen::SparseMatrix<double, Eigen::RowMajor> mixed_B, mixed_lambda;
  bool has_mixed_rows() const { return mixed_B.nonZeros() > 0 || mixed_lambda.nonZeros() > 0; }
  // Whether constraint row k is closed: s_k != 0, or M_B or M_l holds an entry in row k.
  bool closed_row(int k) const;
  // Motions the constraints must hold (K R = 0 up to the terms GMRES
  // absorbs; n x k, orthonormal) and k equations where they are pinned.
  Eigen::MatrixXd rigid_modes;
  std::vector<int> pinned;
  // Optional: every equation the constraint rows may touch in the run (the
  // contact faces' and master faces' control points).  A factorisation
  // orders them last from its first setup on, so that its ordering does not
  // follow the state it first sees: a run restarted at step k factorises as
  // the uninterrupted one did, to the bit.  Empty: the equations B touches
  // at the first setup (fixed from then on).
  std::vector<int> constraint_equations;
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

// J with the constraint rows and the K_coupling inside K, as one block
// (general = true, B empty; Local and the rigid modes kept): for a solver
// that factorises the whole (PETSc's LU) and does not read M_B and M_l.
BlockJacobian as_one_block(const BlockJacobian& J);

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
