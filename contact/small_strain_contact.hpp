// SPDX-License-Identifier: BSD-3-Clause
// Small-deformation frictionless contact: the primal-dual active set method
// of the paper (Appendix 1) on the saddle-point system
//     K u + G^T lambda = f,   (G u)_K = -g0_K for K active,  lambda_K = 0 inactive.
// Each active-set iteration is one linear solve; the iteration stops when the
// active set no longer changes.
//
// How it stays cheap: K is factorised once (CHOLMOD, P K P^T = L L^T) and
// every active-set iteration works on the Schur complement of the ACTIVE
// multipliers only, S_AA = G_A K^-1 G_A^T = Y_A^T Y_A, a small dense matrix,
// with Y_A = L^-1 P G_A^T.  The contact-face equations are ordered last
// (constrained AMD, or nested dissection with the face moved last), so Y_A
// lives in the factor's trailing block: the column of a multiplier costs a
// dense triangular solve of the size of the face, computed once, when the
// multiplier first becomes active, in one blocked pass per iteration
// (engine/cholesky.hpp, forward()).  The weighted gaps of all multipliers
// come from one backward solve on the same block per iteration,
// G K^-1 (f - G_A^T lambda_A) = G P^T L^-T (L^-1 P f - Y_A lambda_A).
// Without the face-last ordering (face_last = false) the same code works on
// the reach of the contact zone in CHOLMOD's own ordering: less fill in the
// factor, but in 3D the reach crosses the top separators, dense blocks far
// larger than the face (hertz3d: 17k rows against 1.1k), so the columns cost
// more than the fill saves.
//
// A body held only by contact has rigid motions R
// (K R = 0): they are pinned while K is factorised and their amplitudes c
// enter the dense system with the equilibrium rows R^T (f - G^T lambda) = 0,
// so the contact force balances the load to round-off:
//     [ S_AA    -G_A R ] [lambda_A]   [ g0_A + G_A K^-1 f ]
//     [-R^T G_A^T   0  ] [   c    ] = [     -R^T f        ]
// Active set rule (paper): K active when lambda_K < 0 or (lambda_K = 0 and
// (Pi g)_K < 0), written as lambda_K + c_n (Pi g)_K < 0 with c_n > 0.
#pragma once

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "contact/weighted_gap.hpp"
#include "engine/cholesky.hpp"
#include "engine/linear_static.hpp"

namespace igac {

struct ContactSolverOptions {
  int max_iterations = 50;
  // c_n in the active-set rule, in units of stress per length (E / size).
  double complementarity_scale = 1.0;
  // The mesh size h of complementarity_scale = E / h: with friction the
  // tangential scale is E / h_K per multiplier in 3D (tangential_scales,
  // contact/small_strain_friction.hpp); 0: the normal scale.
  double mesh_size = 0;
  // Initial active set: weighted initial gap <= this (the paper's 1e-9).
  double initial_gap_tolerance = 1e-9;
  // Order the contact-face equations last (see above).
  bool face_last = true;
  // A start from the solution one mesh coarser (contact/coarse_start): the
  // first active set instead of the closed initial gaps, and for a Krylov
  // solver the first guess.  Empty: no such start.
  std::vector<char> initial_active;
  Eigen::VectorXd initial_u, initial_lambda;
  // Progress: called after each active-set iteration with the iteration
  // (from 0), the size of the set it solved with, how many multipliers
  // change state for the next one (0: converged), and the Krylov iterations
  // of its linear solve (-1 for a direct solve).
  std::function<void(int iteration, int active, int changed, int krylov)> on_iteration;
};

struct ContactSolution {
  Eigen::VectorXd u;                 // free displacements
  Eigen::VectorXd lambda;            // per multiplier, <= 0
  std::vector<char> active;
  Eigen::VectorXd weighted_gap;      // (Pi g)_K at the solution
  std::vector<int> active_set_sizes; // per iteration (the set each solve used)
  // Friction (contact/small_strain_friction.hpp), empty without: dim-1 per
  // multiplier (row K (dim-1) + j along tangent t_j), the tangential
  // multipliers, the slip accumulated over the load steps (weighted, / K_K)
  // and the state of each multiplier (FrictionState: open, stick, slip).
  Eigen::VectorXd lambda_t, slip;
  std::vector<char> friction_state;
  std::vector<int> step_iterations;  // active-set iterations of each load step (active_set_sizes: all of them)
  bool converged = false;
  std::string status;
  double factorize_s = 0, schur_s = 0, iterations_s = 0;
  int schur_columns = 0;             // columns of L^-1 P G^T computed (multipliers ever active)
  int reach_rows = 0;                // rows of the contact face's reach in the factor
  // Iterative linear solvers (solvers/petsc_contact): what ran, and the
  // Krylov iterations of each active-set iteration's solve.
  std::string linear_solver;
  std::vector<int> linear_iterations;
  int ranks = 1;
  double peak_resident_all_ranks_gib = 0;  // summed over the processes
};

// The active set the iteration starts from: options.initial_active when
// given, else the closed initial gaps; a body held
// only by contact (k free rigid motions) starts with at least the k
// multipliers nearest to the obstacle.
std::vector<char> initial_active_set(const WeightedGapOperator& op, int k, const ContactSolverOptions& options);
// The paper's rule (Appendix 1): K active when lambda_K + c_n (Pi g)_K < 0;
// where that is zero to round-off, K keeps its state; and at least k
// multipliers stay active.  The same rule for every linear solver.
// `forced`: how many of those k the rule itself would release (lambda_K +
// c_n (Pi g)_K > 0 beyond round-off): kept only so that the next solve
// holds the body's free rigid motions.  At a settled set such a multiplier
// pulls (lambda_K > 0), and the set is no solution.
std::vector<char> next_active_set(const Eigen::VectorXd& lambda, const Eigen::VectorXd& gap,
                                  const std::vector<char>& active, int k, double cn, int* forced = nullptr);

// One step of the active-set iteration, the same for every linear solver:
// `next` (from next_active_set, with its `forced`) against the current set.
// Returns true when the iteration ends -- the set settled (converged; or
// failed when it holds a body by multipliers in tension, `forced` > 0) or
// came back (cycling), with sol.status set; otherwise records the current
// set in `seen` and moves `active` to `next`.  Reports the iteration to
// options.on_iteration first.
bool settle_active_set(const std::vector<char>& next, std::vector<char>& active, std::set<std::vector<char>>& seen,
                       int iteration, ContactSolution& sol, const ContactSolverOptions& options, int forced = 0);

// A body held only by contact along one free rigid motion r (k = 1): does
// the load pull it off?  The load's work along r, push = r . f, moves the
// body along sign(push) r, which changes the weighted gaps by sign(push) G r
// (`Gr`, the normal rows): when that opens some gap and closes none, no
// multiplier lambda <= 0 (the contact only pushes) balances the load.
// `f_scale`: the load's size, below which push is round-off.
bool load_pulls_off(const Eigen::VectorXd& Gr, double push, double f_scale);
// The status of a solve that stopped because the load pulls a body held only
// by contact off it: seen before the iteration (load_pulls_off, forced = 0)
// or at a set that holds it by `forced` multipliers in tension; `note`
// added to the reason in brackets.
std::string pulled_off_status(int forced = 0, const std::string& note = {});

ContactSolution solve_small_strain_contact(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& f,
                                           const WeightedGapOperator& op, const RigidModes& modes,
                                           SparseCholesky& cholesky, const ContactSolverOptions& options);

}  // namespace igac
