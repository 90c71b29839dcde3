// SPDX-License-Identifier: BSD-3-Clause
// Newton's method on R(x; t) = 0 at one t (engine/nonlinear_problem.hpp),
// driven by SUNDIALS KINSOL: the KINSOL wrapper, apart from the load
// stepping that calls it (engine/load_stepping.hpp), as deal.II keeps its
// KINSOL wrapper apart from what drives it.
//
// KINSOL runs Newton with its line search, without one, or with the
// wrapper's own halving line search (Options::halving_line_search), through
// a custom linear solver that hands each Jacobian, in blocks, to a
// LinearBackend (engine/linear_backend.hpp).  The convergence test is on
// max_i w_i |R_i| / F (the problem's force scale and row weights).  A
// NumericalFailure thrown by the problem for a trial state fails the solve
// with its message; anything else thrown comes out of solve() as itself.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "engine/block_jacobian.hpp"
#include "engine/linear_backend.hpp"
#include "engine/nonlinear_problem.hpp"

namespace igac {

// The path of one Newton solve.
struct NewtonRecord {
  int iterations = 0;
  std::vector<double> residual_norms;  // relative, per iteration, the last the converged one
  std::vector<int> active_set_sizes;   // per iteration
};

class KinsolNewton {
 public:
  struct Options {
    int max_iterations = 30;
    double tolerance = 1e-9;           // on max_i w_i |R_i| / force scale
    bool line_search = true;           // KINSOL's KIN_LINESEARCH, else KIN_NONE
    bool halving_line_search = false;  // the wrapper's own (LoadSteppingOptions::halving_line_search)
    // The inner active-set loop of each Newton step
    // (NonlinearProblem::relinearise_active_set); false: one set per step.
    bool linearised_active_set = true;
  };
  // `problem` and `solver` must outlive this.
  KinsolNewton(NonlinearProblem& problem, LinearBackend& solver, Options options);
  ~KinsolNewton();
  KinsolNewton(const KinsolNewton&) = delete;
  KinsolNewton& operator=(const KinsolNewton&) = delete;

  // Newton from x at t; on success x holds the solution (true), else x is
  // unchanged and failure() says why.  The path is appended to `record`.
  bool solve(double t, Eigen::VectorXd& x, NewtonRecord& record);
  const std::string& failure() const { return failure_; }
  // The block Jacobian the solves assemble into (reused by a tangent
  // predictor: one matrix in memory).
  BlockJacobian& jacobian() { return J_; }
  // Time spent in the problem's residual and Jacobian, over every solve.
  double residual_seconds() const { return residual_seconds_; }
  double jacobian_seconds() const { return jacobian_seconds_; }

 private:
  struct Context;
  NonlinearProblem& problem_;
  LinearBackend& solver_;
  Options options_;
  std::unique_ptr<Context> context_;  // SUNDIALS' context, one for every solve
  BlockJacobian J_;
  std::string failure_;
  double residual_seconds_ = 0, jacobian_seconds_ = 0;
};

}  // namespace igac
