// SPDX-License-Identifier: BSD-3-Clause
// The direct linear backend of the load-stepping driver
// (engine/linear_backend.hpp): the Newton matrix in blocks
// (engine/block_jacobian.hpp) solved on one process.
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
//    R is cut to the combinations some active row holds (B_A R's right
//    singular vectors above round-off): along a motion none holds (a body
//    between frictionless planes sliding along them) J is singular, and the
//    step leaves the body where its pinned equations are;
//  - J is not symmetric when a follower pressure acts (its load stiffness,
//    handed over beside K as K_coupling, which keeps K_s R = 0): the solve
//    of the symmetric-part system preconditions GMRES on J (right
//    preconditioning; the skew part is of the order of the pressure over
//    the stiffness), and GMRES also absorbs what makes K_s R != 0 (the
//    curvature of a curved obstacle) and the rest of K_coupling.  For a
//    symmetric K and no K_coupling one application is exact.
// Rows that combine (BlockJacobian::mixed_B, mixed_lambda: Coulomb
// friction's slip rows) keep the same factor: the closed rows' Schur
// complement C_A K_s^-1 B_A^T - E_AA is not symmetric and its bordered
// system is solved by a dense LU instead of a Cholesky factor.
// When K_s is not positive definite (a buckling state, a law without
// convexity) or GMRES stalls, that Newton iteration falls back to UMFPACK
// on the whole J: never a wrong step, only a slower one.
#pragma once

#include <memory>
#include <string>

#include "engine/linear_backend.hpp"

namespace igac {

class SaddleSolver final : public LinearBackend {
 public:
  SaddleSolver();
  ~SaddleSolver();
  SaddleSolver(const SaddleSolver&) = delete;
  SaddleSolver& operator=(const SaddleSolver&) = delete;

  // Factorises J; J must stay alive (and unchanged) until the next setup.
  // The pattern of K and the set of equations B touches are analysed on the
  // first call.  False (with why()) when J is singular.
  bool setup(const BlockJacobian& J) override;
  // x = J^-1 b, to |J x - b| <= tolerance |b| (infinity norms; 0: as
  // exact as a direct solve).  Only GMRES makes it inexact: a Newton driver
  // asks for tolerance ~ |R| (relative), which keeps Newton quadratic.
  // False (with why()) when the solve fails.
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance = 0) override;
  // New active rows, same K: only their Schur complement is formed again
  // (the LU fallback factorises the whole J again).
  bool update_constraint_rows(const BlockJacobian& J) override;
  const std::string& why() const override { return why_; }
  const LinearSolveStats& stats() const override { return stats_; }
  // kappa_1 of the matrix of the last setup that was factorised: K_s with
  // the rigid motions pinned (engine/condition_estimate.hpp), or on the LU
  // fallback UMFPACK's reciprocal pivot ratio; 0 before any setup.
  double condition_estimate() const override;
  LinearBackendReport report() const override;

 private:
  bool schur_of_active_rows(const BlockJacobian& J);
  bool schur_of_mixed_rows(const BlockJacobian& J);
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string why_;
  LinearSolveStats stats_;
};

}  // namespace igac
