// Small-deformation frictionless contact: the primal-dual active set method
// of the paper (Appendix 1) on the saddle-point system
//     K u + G^T lambda = f,   (G u)_K = -g0_K for K active,  lambda_K = 0 inactive.
// Each active-set iteration is one linear solve; the iteration stops when the
// active set no longer changes.
//
// How it stays cheap: K is factorised once (CHOLMOD) with the contact-face
// equations ordered last, so the dense trailing block L_TT of the factor
// gives the Schur complement of every multiplier at once,
// S = G K^-1 G^T = Y^T Y with Y = L_TT^-1 (P G^T)_T — a dense triangular
// solve of the size of the face.  Every active-set iteration then works on
// S restricted to the active multipliers, a small dense matrix.  (Should
// the ordering not keep the face apart, columns of S come from sparse
// solves, computed only when a multiplier first becomes active.)  A body
// held only by contact has rigid motions R
// (K R = 0): they are pinned while K is factorised and their amplitudes c
// enter the dense system with the equilibrium rows R^T (f - G^T lambda) = 0,
// so the contact force balances the load to round-off:
//     [ S_AA    -G_A R ] [lambda_A]   [ g0_A + G_A K^-1 f ]
//     [-R^T G_A^T   0  ] [   c    ] = [     -R^T f        ]
// Active set rule (paper): K active when lambda_K < 0 or (lambda_K = 0 and
// (Pi g)_K < 0), written as lambda_K + c_n (Pi g)_K < 0 with c_n > 0.
#pragma once

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
  // Initial active set: weighted initial gap <= this (the paper's 1e-9).
  double initial_gap_tolerance = 1e-9;
  // Schur complement from the factor's trailing block (false: one sparse
  // solve per multiplier that becomes active, the fallback used when the
  // ordering cannot keep the face apart).
  bool schur_from_factor = true;
};

struct ContactSolution {
  Eigen::VectorXd u;                 // free displacements
  Eigen::VectorXd lambda;            // per multiplier, <= 0
  std::vector<char> active;
  Eigen::VectorXd weighted_gap;      // (Pi g)_K at the solution
  std::vector<int> active_set_sizes; // per iteration (the set each solve used)
  bool converged = false;
  std::string status;
  double factorize_s = 0, schur_s = 0, iterations_s = 0;
  int schur_columns = 0;             // sparse solves spent on S
  // Iterative linear solvers (contact/petsc_contact): what ran, and the
  // Krylov iterations of each active-set iteration's solve.
  std::string linear_solver;
  std::vector<int> linear_iterations;
  int ranks = 1;
  double peak_resident_all_ranks_gib = 0;  // summed over the processes
};

// The active set the iteration starts from: closed initial gaps; a body held
// only by contact (k free rigid motions) starts with at least the k
// multipliers nearest to the obstacle.
std::vector<char> initial_active_set(const WeightedGapOperator& op, int k, const ContactSolverOptions& options);
// The paper's rule (Appendix 1): K active when lambda_K + c_n (Pi g)_K < 0;
// where that is zero to round-off, K keeps its state; and at least k
// multipliers stay active.  The same rule for every linear solver.
std::vector<char> next_active_set(const Eigen::VectorXd& lambda, const Eigen::VectorXd& gap,
                                  const std::vector<char>& active, int k, double cn);

ContactSolution solve_small_strain_contact(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& f,
                                           const WeightedGapOperator& op, const RigidModes& modes,
                                           SparseCholesky& cholesky, const ContactSolverOptions& options);

}  // namespace igac
