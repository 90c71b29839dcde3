// SPDX-License-Identifier: BSD-3-Clause
// Load stepping: the increments, cut-backs, predictors and augmentations
// around Newton's method, which KinsolNewton (engine/kinsol_newton.hpp, the
// SUNDIALS KINSOL wrapper) runs at each step.
//
// The driver knows a nonlinear problem only through NonlinearProblem
// (engine/nonlinear_problem.hpp): the
// residual R(x; t) at load factor t and its Jacobian (same sparsity pattern on
// every call).  Contact enters through that interface (its multipliers are
// part of x and its active set is decided from x inside the residual and the
// Jacobian: a semismooth Newton method), so engine/ never includes contact/.
//
// KINSOL runs Newton (with its line search, without, or with the wrapper's
// own halving one, LoadSteppingOptions::halving_line_search) through a custom
// linear solver, a LinearBackend (engine/linear_backend.hpp) the caller may
// inject (LoadSteppingOptions::linear_backend: PETSc's, solvers/); by
// default the direct one, SaddleSolver (engine/saddle_solver.hpp): the
// problem hands over its Jacobian in blocks (the displacement block K, the
// constraint rows), K's symmetric part is factorised by CHOLMOD with the
// symbolic analysis done once for the whole run, the active multipliers are
// eliminated through a small dense Schur complement, and GMRES takes care of
// K's skew part (a follower load); UMFPACK on the whole matrix is the
// fallback when K's symmetric part is not positive definite.
//
// Steps: the case gives a number of steps (or a first increment); with load
// curves t is their time and steps end on every corner (LoadSteppingOptions::corners).  A step
// that fails — no convergence within the iteration limit, an inadmissible
// state (det F <= 0) in the residual, an active set that cycles — is cut
// back (increment halved) and retried from the last converged state; a step
// that converged in few iterations lets the next one grow; below the minimum
// increment the run ends with a clear status.  Nothing non-finite is kept.
//
// Exceptions: a problem may throw NumericalFailure (engine/numerical_failure.hpp)
// from its residual or Jacobian for a trial state it cannot evaluate; the
// step fails with that message, as when it returns false.  Anything else
// thrown there (a bug, std::bad_alloc) leaves run_load_steps as itself, x
// holding the last converged state.
#pragma once

#include "engine/run_status.hpp"

#include <Eigen/Sparse>
#include <functional>
#include <optional>

#include "engine/kinsol_newton.hpp"
#include "engine/linear_backend.hpp"
#include "engine/nonlinear_problem.hpp"
#include "engine/saddle_solver.hpp"
#include <string>
#include <vector>

namespace igac {

// Where the driver stands between two steps: everything the next step
// depends on, so that a run continued from it (a restart) takes the same
// steps, bit for bit, as one that never stopped.
struct LoadSteppingState {
  double t = 0;       // the time reached
  double dt = 0;      // the increment the next step tries
  double dt_old = 0;  // the last increment (0: none to extrapolate; the tangent predictor)
  Eigen::VectorXd x, x_old;  // the converged state at t, and the one before
};

struct LoadSteppingOptions {
  int steps = 10;                  // initial increment 1/steps ...
  double first_increment = 0;      // ... unless this is > 0
  double min_increment = 1e-6;
  double max_increment = 1.0;
  int max_newton_iterations = 30;
  int fast_iterations = 5;         // a step this fast lets the next grow
  double growth = 1.5;
  double tolerance = 1e-9;         // on |R|_inf / force scale
  bool line_search = true;         // KINSOL's KIN_LINESEARCH, else KIN_NONE
  // The driver's own line search instead (line_search is then ignored):
  // from the full Newton step, halve the step length s until the state is
  // admissible and |R(x + s d)|_2 <= (1 - 1e-4 s) |R(x)|_2 (Armijo).  KINSOL's
  // backtracking fits a quadratic to |R|^2 and takes s >= 0.1 of the last
  // try: where the full step raises |R| tenfold (a nearly incompressible
  // solid: the volumetric residual K (J - 1) is second order in the step,
  // times K) it settles on s = 0.1 at every iteration, where s = 1/4 or 1/2
  // would already decrease |R| (docs/benchmarks.md, "Real rubber").
  bool halving_line_search = false;
  bool tangent_predictor = true;   // a step without history starts from x - J^{-1} dR/dt dt
  // Every step starts from the tangent predictor, not from the last
  // increment extrapolated (one more factorisation per step).
  bool tangent_every_step = false;
  // Each Newton step solves the linearised contact problem to its own
  // active set (KinsolNewton::Options::linearised_active_set).
  bool linearised_active_set = true;
  bool quiet = false;
  // Load curves (engine/load_curve.hpp): the times t runs through, the
  // curves' corners in increasing order, the last where the run ends.  A
  // step never straddles one: it is cut to end on it (and the next step
  // starts from the increment before that cut, with the tangent predictor
  // rather than extrapolating across the corner).  Empty: t runs from 0 to
  // 1, the load factor.
  std::vector<double> corners;
  // A restart: start from this state instead of (t = 0, x); `steps_done`
  // steps count as done (for max_steps).
  std::optional<LoadSteppingState> start;
  int steps_done = 0;
  // Stop once this many steps are done (0: no limit), with the status
  // "stopped after step N (as asked)".
  int max_steps = 0;
  // Augmented-Lagrangian rounds per step at most (NonlinearProblem::augment);
  // more fails the step (cut back).
  int max_augmentations = 30;
  // Called after each converged step, before on_step, with the state to
  // continue from.
  std::function<void(const LoadSteppingState&)> on_state;
  // The linear solver of every Newton step (not owned; it must outlive the
  // run).  Null: the direct SaddleSolver, one for the run.
  LinearBackend* linear_backend = nullptr;
};

struct LoadStepRecord {
  double load_factor = 0;  // the time t (with load curves, the curves' abscissa)
  int newton_iterations = 0;
  std::vector<double> residual_norms;  // relative, per Newton iteration, last = converged
  std::vector<int> active_set_sizes;   // per Newton iteration
  int cut_backs = 0;                   // failed attempts before this step converged
  int augmentations = 0;               // NonlinearProblem::augment rounds (each a Newton solve more)
};

struct LoadSteppingSummary {
  RunStatus status;  // (engine/run_status.hpp; set when the run ends)
  std::vector<LoadStepRecord> steps;
  int unfinished_cut_backs = 0;  // a failed run: the cut-backs after its last converged step
  double newton_seconds = 0;
  double residual_seconds = 0, jacobian_seconds = 0;  // inside newton_seconds
  LinearSolveStats linear;                           // the linear solves, ditto
  // kappa_1 of the last Newton matrix factorised (LinearBackend::condition_estimate):
  // how many digits of the result round-off leaves; 0 when nothing was solved.
  double condition_estimate = 0;
};

// Runs from x (the state at t = 0) to t = 1 (with corners, to the last);
// x holds the last converged state on return.  `on_step` is called after each converged step.
LoadSteppingSummary run_load_steps(NonlinearProblem& problem, Eigen::VectorXd& x, const LoadSteppingOptions& options,
                                   const std::function<void(const LoadStepRecord&, const Eigen::VectorXd&)>& on_step);

}  // namespace igac
