// SPDX-License-Identifier: BSD-3-Clause
// The linear solver behind the load-stepping Newton driver
// (engine/load_stepping.hpp), injected: the driver decides what to solve
// (the Newton step, the tangent predictor) and a backend how.  Two exist:
//  - SaddleSolver (engine/saddle_solver.hpp), the direct one: CHOLMOD on the
//    displacement block's symmetric part, the active multipliers through a
//    dense Schur complement, GMRES for the skew part, UMFPACK as fallback;
//  - PetscNewtonSolver (solvers/petsc_newton.hpp): the condensed Newton
//    matrix in PETSc, on one or more MPI processes (MUMPS LU by default, or
//    any KSP and PC the PETSc options name).
// A backend sees the matrix in blocks (engine/block_jacobian.hpp) and
// decides what to assemble from them.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "engine/block_jacobian.hpp"

namespace igac {

struct LinearSolveStats {
  // shifted: setups whose preconditioner factorised K_s plus |K_ii| at the
  // equations whose pivot failed (K_s indefinite; engine/saddle_solver.cpp);
  // fallbacks: LU of the whole J
  int setups = 0, solves = 0, krylov_iterations = 0, fallbacks = 0, shifted = 0;
  double factorize_s = 0, schur_s = 0, solve_s = 0;
};

// What a run reports of its linear solver (summary.json "solver").
struct LinearBackendReport {
  std::string type = "direct";         // direct | petsc
  std::string method;                  // e.g. "preonly + lu (mumps)"
  std::vector<int> iterations;         // Krylov iterations per solve (empty: a direct solve)
  int ranks = 1;
  double peak_resident_all_ranks_gib = 0;  // 0: not measured
};

class LinearBackend {
 public:
  virtual ~LinearBackend() = default;
  // Takes J (which must stay alive and unchanged until the next setup) and
  // prepares its solves.  False (with why()) when J is singular.
  virtual bool setup(const BlockJacobian& J) = 0;
  // x = J^-1 b for the whole J (local unknowns included), to
  // |J x - b| <= tolerance |b| where the backend is iterative (0: as tight
  // as it goes); a direct factorisation is exact to round-off whatever the
  // tolerance.  False (with why()) when the solve fails.
  virtual bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance) = 0;
  // J's constraint rows (s and d, engine/block_jacobian.hpp) changed since
  // setup, nothing else did: prepare the solves again.  A backend that
  // factorises K apart from the constraints (SaddleSolver) redoes only the
  // active rows' Schur complement; the default sets up anew.
  virtual bool update_constraint_rows(const BlockJacobian& J) { return setup(J); }
  virtual const std::string& why() const = 0;
  virtual const LinearSolveStats& stats() const = 0;
  // kappa_1 of the last matrix factorised, estimated; 0: not estimated.
  virtual double condition_estimate() const = 0;
  virtual LinearBackendReport report() const = 0;
};

}  // namespace igac
