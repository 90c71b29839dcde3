// SPDX-License-Identifier: BSD-3-Clause
// The Newton matrix of a problem with constraints, in blocks, and its direct
// solver (used by the load-stepping driver, engine/load_stepping.hpp).
//
//   J = [ K            B^T     ]   K: n x n (symmetric pattern), B: m x n,
//       [ diag(s) B    diag(d) ]   and per constraint row k either s_k = 0
//                                  (inactive: d_k dl_k = b_k) or d_k = 0
//                                  (active: s_k B_k du = b_k).
//
// This is the semismooth-Newton matrix of weighted-gap contact
// (model/finite_strain_problem.hpp): B holds the gap derivatives, s the scale c of
// the active rows, d the weights of the inactive ones.
//
// How it is solved, per Newton iteration (the small-deformation contact
// solve, contact/small_strain_contact.hpp, does the same once):
//  - K_s = (K + K^T) / 2 with the rigid motions R of the body pinned is
//    factorised by CHOLMOD, L L^T, symbolic analysis once, with the
//    equations B touches ordered last (the factor's trailing block);
//  - the active multipliers are eliminated through their Schur complement
//    S_AA = B_A K_s^-1 B_A^T = Y^T Y, Y = L^-1 P B_A^T computed on the reach
//    of B_A only (engine/cholesky.hpp), and the rigid amplitudes c through
//    the equilibrium rows R^T (f - B_A^T l_A) = 0:
//      [ S_AA       -B_A R ] [l_A]   [ B_A K_s^-1 f - b_A / s_A ]
//      [ -R^T B_A^T    0   ] [ c ] = [ -R^T f                   ],
//    then du = K_s^-1 (f - B_A^T l_A) + R c (one forward, one backward solve);
//  - K itself is not symmetric when a follower pressure acts (its load
//    stiffness): the solve of that symmetric-part system preconditions GMRES
//    on J (right preconditioning; the skew part is of the order of the
//    pressure over the stiffness), and GMRES also absorbs what makes
//    K_s R != 0 (the curvature of a curved obstacle) and K_coupling.  A problem may hand
//    over the symmetric matrix to factorise (K_factor; the large-deformation
//    problem gives K without the follower load stiffness, which keeps
//    K_s R = 0).  For a symmetric K one application is exact.
// When K_s is not positive definite (a buckling state, a law without
// convexity) or GMRES stalls, that Newton iteration falls back to UMFPACK
// on the whole J: never a wrong step, only a slower one.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <memory>
#include <string>
#include <vector>

namespace igac {

struct BlockJacobian {
  Eigen::SparseMatrix<double> K;
  // Optional: the symmetric matrix to factorise in K's place (K's pattern);
  // empty: (K + K^T) / 2.
  Eigen::SparseMatrix<double> K_factor;
  // Optional: a part of the displacement block outside K's pattern, so
  // that J's K is K + K_coupling (empty: none).  The factor leaves it out
  // and GMRES applies it, as it does the follower load's skew part: the
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

struct SaddleSolverStats {
  int setups = 0, solves = 0, krylov_iterations = 0, fallbacks = 0;
  double factorize_s = 0, schur_s = 0, solve_s = 0;
};

class SaddleSolver {
 public:
  SaddleSolver();
  ~SaddleSolver();
  SaddleSolver(const SaddleSolver&) = delete;
  SaddleSolver& operator=(const SaddleSolver&) = delete;

  // Factorises J; J must stay alive (and unchanged) until the next setup.
  // The pattern of K and the set of equations B touches are analysed on the
  // first call.  False (with why()) when J is singular.
  bool setup(const BlockJacobian& J);
  // x = J^-1 b, to |J x - b| <= tolerance |b| (infinity norms; 0: as
  // exact as a direct solve).  Only GMRES makes it inexact: a Newton driver
  // asks for tolerance ~ |R| (relative), which keeps Newton quadratic.
  // False (with why()) when the solve fails.
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance = 0);
  const std::string& why() const { return why_; }
  const SaddleSolverStats& stats() const { return stats_; }
  // kappa_1 of the matrix of the last setup that was factorised: K_s with
  // the rigid motions pinned (engine/condition_estimate.hpp), or on the LU
  // fallback UMFPACK's reciprocal pivot ratio; 0 before any setup.
  double condition_estimate() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string why_;
  SaddleSolverStats stats_;
};

}  // namespace igac
