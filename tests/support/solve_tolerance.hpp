// SPDX-License-Identifier: BSD-3-Clause
// How closely two runs of one case must agree: the one rule every test that
// compares a run with a record or with another run follows, whatever
// processor, BLAS kernel or thread count runs it.
//
// A direct solve is backward stable: the computed x solves (A + dA) x = b
// with ||dA|| <= c eps ||A||, so ||x - x_exact|| <= c eps kappa(A) ||x||
// (Higham, Accuracy and Stability of Numerical Algorithms, ch. 7 and 10).
// Another machine sums in another order (another BLAS kernel in CHOLMOD's
// supernodes, another thread count in the assembly) and computes another
// such x: the two agree to 2 c eps kappa ||x||.  The bound is normwise: an
// entry small beside the largest of its kind (a reaction component that is
// round-off, the pressure at the contact edge) is known to eps kappa times
// that largest, not to eps kappa times itself.  kappa is the run's own
// estimate, summary.json solver.condition_estimate (engine/
// condition_estimate.hpp; the larger of the two runs').
//
// Newton: near the solution the Newton map x -> x - J^-1 R(x) is a
// contraction (its derivative vanishes at the root), so the round-off of
// one iteration is damped by the next and the last iterate of two machines
// agrees to the same bound, over any number of iterations and load steps.
// Krylov (PETSc): the solve stops at ||r|| <= rtol ||b||, which leaves
// kappa rtol of the solution undecided: that, not round-off, is then the
// tolerance (kappa of the direct run of the same case).
//
// Counts (dofs, active-set iterations and sizes of the small-deformation
// solves, load steps, cut-backs) are compared exactly: each is decided by
// comparing a quantity with a threshold (lambda + c g with 0, a step's
// convergence), and in the recorded runs those quantities sit many times
// the bound above from their thresholds (scripts/portability.sh runs the
// whole suite under four BLAS kernels and two thread counts to show it).
// A Newton step's path is not a count of that kind: the iterations from a
// predicted state far from the solution amplify round-off before the
// contraction damps it, and a decision on the way (an attempt that fails
// and is retried from the last state, a line-search cut) can go either
// way on another thread count (measured: oring_on_plate's first step takes
// 6 iterations on one thread, 7 on two); its solution still agrees to the
// bound.  So a load step's Newton iterations, residual history and
// active-set sizes on the way are not compared, its solution is.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

namespace igac_test {

// c above, and the margin for the estimate's being a lower bound (within a
// factor 3 of kappa in practice, Higham sec. 15.3): the measured spread of
// the shipped cases under four BLAS kernels and two thread counts is below
// 0.1 of eps kappa (scripts/portability.sh).
constexpr double kRoundOffSafety = 10;
constexpr double kEps = std::numeric_limits<double>::epsilon();

struct SolveAccuracy {
  double condition = 1;            // kappa_1 estimate (>= 1)
  double iterative_tolerance = 0;  // a Krylov solve's relative tolerance; 0 for a direct solve

  // The relative (normwise) tolerance two runs of the case are held to.
  double relative() const { return kRoundOffSafety * condition * (kEps + iterative_tolerance); }
};

// The largest "condition_estimate" anywhere in a summary.json or study.json
// (a study: one per level); 1 when there is none.
inline double largest_condition_estimate(const nlohmann::json& j) {
  double best = 1;
  if (j.is_object()) {
    for (const auto& [key, v] : j.items())
      best = std::max(best, key == "condition_estimate" && v.is_number() ? v.get<double>() : largest_condition_estimate(v));
  } else if (j.is_array()) {
    for (const auto& v : j) best = std::max(best, largest_condition_estimate(v));
  }
  return best;
}

// Two runs' accuracy: the larger conditioning of the two.
inline SolveAccuracy solve_accuracy(const nlohmann::json& a, const nlohmann::json& b, double iterative_tolerance = 0) {
  return {std::max(largest_condition_estimate(a), largest_condition_estimate(b)), iterative_tolerance};
}

// |a - b| <= tol.relative() * scale, scale the largest |value| of the
// quantity's kind (at least |a| and |b|).
inline bool agree(double a, double b, double scale, const SolveAccuracy& tol) {
  if (a == b) return true;  // infinities, exact zeros
  return std::abs(a - b) <= tol.relative() * std::max({scale, std::abs(a), std::abs(b)});
}

}  // namespace igac_test
