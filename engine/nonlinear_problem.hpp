// SPDX-License-Identifier: BSD-3-Clause
// A nonlinear problem R(x; t) = 0 as the Newton solver (engine/kinsol_newton.hpp)
// and the load-stepping driver (engine/load_stepping.hpp) see it: the
// residual at load factor (or time) t, its Jacobian in blocks
// (engine/block_jacobian.hpp), the contact active set decided from x, and
// the hooks of an augmented Lagrangian and of a path-dependent problem.
#pragma once

#include <string>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <vector>

#include "engine/block_jacobian.hpp"

namespace igac {

class NonlinearProblem {
 public:
  virtual ~NonlinearProblem() = default;
  virtual int size() const = 0;
  // R(x; t).  Return false (or throw NumericalFailure) for an inadmissible
  // state (recoverable).
  virtual bool residual(double t, const Eigen::VectorXd& x, Eigen::VectorXd& r) = 0;
  // dR/dx at (x; t), always with the same pattern.  False: inadmissible.
  virtual bool jacobian(double t, const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& J) = 0;
  // The same in blocks (engine/saddle_solver.hpp), what the driver uses.
  // The default wraps jacobian(): K is the whole matrix, no constraints.
  virtual bool block_jacobian(double t, const Eigen::VectorXd& x, BlockJacobian& J) {
    J.B.resize(0, size());
    J.s.resize(0);
    J.d.resize(0);
    return jacobian(t, x, J.K);
  }
  // Size of the contact active set at (x; t) (0 without contact), for reports.
  virtual int active_set_size(double t, const Eigen::VectorXd& x) const { return 0; }
  // A fingerprint of the active set at (x; t), to detect cycling: a function
  // of (x; t) alone, whatever was called before.
  virtual std::vector<char> active_set(double t, const Eigen::VectorXd& x) const { return {}; }
  // The active set of the Newton step's linearisation.  dx solves J dx = rhs
  // for the J of the last block_jacobian (rhs = -R there, its constraint
  // rows as J's set reads them); decide the set again on the linearised
  // gaps and multipliers of x + dx.  Where a row's decision differs, its
  // row of J (s, d) and of rhs are those of the other decision, and true
  // is returned: the driver solves again with the same K (an inner
  // primal-dual active-set loop, which solves the linearised contact
  // problem instead of taking one semismooth step per change of set).
  // False: the set is settled, or the problem has none.
  virtual bool relinearise_active_set(const Eigen::VectorXd& dx, BlockJacobian& J, Eigen::VectorXd& rhs) {
    static_cast<void>(dx), static_cast<void>(J), static_cast<void>(rhs);
    return false;
  }
  // Force scale at (x; t) for the relative residual (e.g. |f_ext| + |f_int|).
  virtual double force_scale(double t, const Eigen::VectorXd& x) = 0;
  // Per row, the weight of |R_i| in the convergence test (and the residual
  // norms recorded), max_i w_i |R_i| / force scale <= tolerance; the line
  // search measures R unweighted.  Empty: every row 1.
  virtual Eigen::VectorXd residual_weights() const { return {}; }
  // An augmented Lagrangian (an incompressible solid, engine/total_lagrangian.hpp):
  // called once Newton has converged at (t, x); the problem updates its
  // multipliers from x and returns true when the step must be solved again
  // with them (its constraint not met yet).  Then keep_augmentation(true)
  // when the step is accepted, (false) when it failed and is cut back (back
  // to the multipliers of the last accepted step).  Default: none.
  virtual bool augment(double t, const Eigen::VectorXd& x) {
    static_cast<void>(t), static_cast<void>(x);
    return false;
  }
  virtual void keep_augmentation(bool accepted) { static_cast<void>(accepted); }
  // What the last augment() that returned true left unsettled, for the
  // message of a step that runs out of augmentations.
  virtual std::string unsettled_augmentation() const { return "the constraint is not met"; }
  // The converged state (t, x) the next step starts from (t = 0: the
  // initial state), told before that step is tried, and again before each
  // retry after a cut-back: what a path-dependent problem (friction's slip
  // increments over the step) counts from.
  virtual void begin_step(double t, const Eigen::VectorXd& x) {}
};

}  // namespace igac
