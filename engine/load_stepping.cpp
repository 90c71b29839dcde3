// SPDX-License-Identifier: BSD-3-Clause
#include "engine/load_stepping.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <fmt/format.h>
#include <memory>
#include <optional>
#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include "engine/numerical_failure.hpp"
#include "engine/progress_bar.hpp"
#include "engine/stopwatch.hpp"

namespace igac {
namespace {

// Everything one KINSOL solve (one load-step attempt) works with.
struct Attempt {
  NonlinearProblem& problem;
  double t = 0;
  double scale = 1;  // force scale: residuals are relative to it
  BlockJacobian& J;
  LinearBackend& solver;
  LoadSteppingSummary& summary;  // accumulates the time spent in callbacks
  LoadStepRecord record;
  std::vector<std::vector<char>> active_history;
  std::string failure;        // why the attempt failed (an expected, numerical reason)
  std::exception_ptr error;   // anything else thrown in a callback: rethrown once KINSOL returns
  // The halving line search (LoadSteppingOptions::halving_line_search):
  // KINSOL runs plain Newton and the linear solve returns the step the
  // search accepted, from the state of the last Jacobian; its residual is
  // kept for KINSOL's evaluation at the same state, which follows.
  bool halving = false;
  Eigen::VectorXd x_jacobian, x_accepted, r_accepted;
  Eigen::VectorXd weights;  // NonlinearProblem::residual_weights (empty: 1)
  // max_i w_i |R_i| / scale: what the convergence test measures
  double relative(const Eigen::VectorXd& r) const {
    if (r.size() == 0) return 0;
    return (weights.size() ? r.cwiseAbs().cwiseProduct(weights).maxCoeff() : r.cwiseAbs().maxCoeff()) / scale;
  }
};

Eigen::Map<Eigen::VectorXd> view(N_Vector v) { return {N_VGetArrayPointer(v), N_VGetLength(v)}; }

// KINSOL calls back through C frames, which an exception must not cross:
// every callback runs its body through this barrier, which turns an
// exception into KINSOL's unrecoverable return code.  A NumericalFailure
// (engine/numerical_failure.hpp) is an expected outcome of a trial state:
// its message is the attempt's failure, and the step is cut back.  Anything
// else (a bug: std::logic_error, std::out_of_range; std::bad_alloc) is kept
// as it is and rethrown by solve_step once KINSOL has returned, so it leaves
// run_load_steps with its own type instead of becoming a "failed" run.
template <class Body>
int guarded(Attempt& a, Body&& body) noexcept {
  if (a.error) return -1;  // KINSOL stops at the first negative return; never evaluate past an error
  try {
    return body();
  } catch (const NumericalFailure& e) {
    a.failure = e.what();
  } catch (...) {
    a.error = std::current_exception();
  }
  return -1;
}

// RAII owners of the SUNDIALS objects of one solve.
struct NVectorDeleter {
  void operator()(_generic_N_Vector* v) const { N_VDestroy(v); }
};
using NVectorPtr = std::unique_ptr<_generic_N_Vector, NVectorDeleter>;
struct KinsolDeleter {
  void operator()(void* kin) const { KINFree(&kin); }
};
using KinsolPtr = std::unique_ptr<void, KinsolDeleter>;
struct LinearSolverDeleter {
  void operator()(_generic_SUNLinearSolver* s) const { SUNLinSolFree(s); }
};
using LinearSolverPtr = std::unique_ptr<_generic_SUNLinearSolver, LinearSolverDeleter>;
struct MatrixDeleter {
  void operator()(_generic_SUNMatrix* m) const { SUNMatDestroy(m); }
};
using MatrixPtr = std::unique_ptr<_generic_SUNMatrix, MatrixDeleter>;
struct ContextOwner {
  SUNContext ctx = nullptr;
  ContextOwner() { SUNContext_Create(nullptr, &ctx); }
  ~ContextOwner() { SUNContext_Free(&ctx); }
  ContextOwner(const ContextOwner&) = delete;
  ContextOwner& operator=(const ContextOwner&) = delete;
};

int residual_body(Attempt& a, N_Vector u, N_Vector f);
int jacobian_body(Attempt& a, N_Vector u, N_Vector fu);
int ls_setup_body(Attempt& a);
int ls_solve_body(Attempt& a, N_Vector x, N_Vector b);

int residual_fn(N_Vector u, N_Vector f, void* data) {
  auto& a = *static_cast<Attempt*>(data);
  return guarded(a, [&] { return residual_body(a, u, f); });
}

int residual_body(Attempt& a, N_Vector u, N_Vector f) {
  Eigen::VectorXd x = view(u), r;
  if (a.halving && a.x_accepted.size() == x.size() && x == a.x_accepted) {
    view(f) = a.r_accepted;
    return 0;
  }
  const Stopwatch clock;
  const bool ok = a.problem.residual(a.t, x, r);
  a.summary.residual_seconds += clock.seconds();
  if (!ok || !r.allFinite()) {
    a.failure = "inadmissible state (det F <= 0 or a non-finite residual)";
    return 1;  // recoverable: the line search shortens the step
  }
  view(f) = r;
  return 0;
}

int jacobian_fn(N_Vector u, N_Vector fu, SUNMatrix, void* data, N_Vector, N_Vector) {
  auto& a = *static_cast<Attempt*>(data);
  return guarded(a, [&] { return jacobian_body(a, u, fu); });
}

int jacobian_body(Attempt& a, N_Vector u, N_Vector fu) {
  const Eigen::VectorXd x = view(u);
  if (a.halving) a.x_jacobian = x;
  a.record.residual_norms.push_back(a.relative(view(fu)));
  const auto set = a.problem.active_set(a.t, x);
  a.record.active_set_sizes.push_back(int(std::count(set.begin(), set.end(), 1)));
  // Active-set cycling: the same set seen again after a different one, with
  // no progress in between, is a loop Newton will not leave.
  if (!set.empty()) {
    const auto& h = a.active_history;
    if (h.size() >= 3 && set == h[h.size() - 2] && h.back() != set && h[h.size() - 3] == h.back()) {
      a.failure = "active set cycling";
      return -1;
    }
    a.active_history.push_back(set);
  }
  const Stopwatch clock;
  const bool ok = a.problem.block_jacobian(a.t, x, a.J);
  a.summary.jacobian_seconds += clock.seconds();
  if (!ok) {
    a.failure = "inadmissible state in the Jacobian";
    return -1;
  }
  return 0;
}

// A direct linear solver for KINSOL: SaddleSolver on the Jacobian blocks
// the problem assembled (the SUNMatrix handed around is an empty placeholder).
int ls_setup(SUNLinearSolver S, SUNMatrix) {
  auto& a = *static_cast<Attempt*>(S->content);
  return guarded(a, [&] { return ls_setup_body(a); });
}

int ls_setup_body(Attempt& a) {
  if (!a.solver.setup(a.J)) {
    a.failure = a.solver.why();
    return -1;
  }
  return 0;
}

int ls_solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype) {
  auto& a = *static_cast<Attempt*>(S->content);
  return guarded(a, [&] { return ls_solve_body(a, x, b); });
}

// The halving line search from a.x_jacobian along the Newton step d (the
// residual there is -minus_r0): the step s d it accepts, or false (no
// admissible decrease down to s = 2^-kHalvings).
bool halving_search(Attempt& a, const Eigen::VectorXd& minus_r0, const Eigen::VectorXd& d, Eigen::VectorXd& step) {
  constexpr int kHalvings = 30;
  constexpr double kArmijo = 1e-4;  // KINSOL's alpha
  const double f0 = minus_r0.norm();
  double s = 1;
  Eigen::VectorXd r;
  for (int k = 0; k <= kHalvings; ++k, s *= 0.5) {
    step = s * d;
    Eigen::VectorXd x = a.x_jacobian + step;  // what KINSOL forms (u + step), bit for bit
    const Stopwatch clock;
    bool ok = false;
    try {
      ok = a.problem.residual(a.t, x, r) && r.allFinite();
    } catch (const NumericalFailure&) {
      ok = false;  // an inadmissible trial state: shorter
    }
    a.summary.residual_seconds += clock.seconds();
    if (ok && r.norm() <= (1 - kArmijo * s) * f0) {
      a.x_accepted = std::move(x);
      a.r_accepted = r;
      return true;
    }
  }
  return false;
}

int ls_solve_body(Attempt& a, N_Vector x, N_Vector b) {
  const Eigen::VectorXd rhs = view(b);  // -R
  // Inexact Newton (only where the solver iterates): a linear residual below
  // 0.1 |R|/F of |R| leaves the next residual ~ |R|^2, Newton stays quadratic.
  const double tolerance = std::min(1e-3, 0.1 * rhs.cwiseAbs().maxCoeff() / a.scale);
  Eigen::VectorXd sol;
  if (!a.solver.solve(rhs, sol, tolerance)) {
    a.failure = a.solver.why();
    return -1;
  }
  if (a.halving) {
    Eigen::VectorXd step;
    if (!halving_search(a, rhs, sol, step)) {
      a.failure = "the line search found no decrease";
      return -1;
    }
    sol = std::move(step);
  }
  view(x) = sol;
  return 0;
}

void silent(int, const char*, const char*, char*, void*) {}

// One load-step attempt from x at load factor t; x is updated on success.
bool solve_step(Attempt& a, Eigen::VectorXd& x, SUNContext ctx, const LoadSteppingOptions& opt) {
  const int n = int(x.size());
  const NVectorPtr u_owner(N_VNew_Serial(n, ctx)), us_owner(N_VNew_Serial(n, ctx)), fs_owner(N_VNew_Serial(n, ctx));
  N_Vector u = u_owner.get(), us = us_owner.get(), fs = fs_owner.get();
  view(u) = x;
  N_VConst(1.0, us);
  a.scale = std::max(a.problem.force_scale(a.t, x), 1e-300);
  a.weights = a.problem.residual_weights();
  if (a.weights.size() == n) view(fs) = a.weights / a.scale;
  else N_VConst(1.0 / a.scale, fs), a.weights.resize(0);
  // The matrix and the linear solver are declared before the KINSOL memory
  // so that KINFree runs first, while they still exist.
  const MatrixPtr A(SUNMatNewEmpty(ctx));
  A->ops->getid = [](SUNMatrix) { return SUNMATRIX_CUSTOM; };
  A->ops->zero = [](SUNMatrix) { return 0; };
  A->ops->destroy = [](SUNMatrix M) { SUNMatFreeEmpty(M); };
  const LinearSolverPtr LS(SUNLinSolNewEmpty(ctx));
  LS->content = &a;
  LS->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
  LS->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
  LS->ops->setup = ls_setup;
  LS->ops->solve = ls_solve;
  LS->ops->free = [](SUNLinearSolver S) {
    S->content = nullptr;
    SUNLinSolFreeEmpty(S);
    return 0;
  };
  const KinsolPtr kin_owner(KINCreate(ctx));
  void* kin = kin_owner.get();
  KINInit(kin, residual_fn, u);
  KINSetUserData(kin, &a);
  KINSetErrHandlerFn(kin, silent, nullptr);
  KINSetLinearSolver(kin, LS.get(), A.get());
  KINSetJacFn(kin, jacobian_fn);
  KINSetMaxSetupCalls(kin, 1);  // a fresh Jacobian at every iteration: Newton, not chord
  KINSetNumMaxIters(kin, opt.max_newton_iterations);
  KINSetFuncNormTol(kin, opt.tolerance);
  KINSetScaledStepTol(kin, 1e-15);
  a.halving = opt.halving_line_search;
  if (a.halving) KINSetMaxNewtonStep(kin, 1e300);  // the search shortens the step, KINSOL must not
  const int flag = KINSol(kin, u, opt.line_search && !a.halving ? KIN_LINESEARCH : KIN_NONE, us, fs);
  if (a.error) std::rethrow_exception(a.error);  // the SUNDIALS objects are freed on the way out
  long iterations = 0;
  KINGetNumNonlinSolvIters(kin, &iterations);
  double fnorm = NAN;
  KINGetFuncNorm(kin, &fnorm);
  const Eigen::VectorXd x_new = view(u);
  a.record.newton_iterations = int(iterations);
  const bool ok = flag >= 0 && std::isfinite(fnorm) && fnorm <= 10 * opt.tolerance && x_new.allFinite();
  if (!ok && a.failure.empty())
    a.failure = flag == KIN_MAXITER_REACHED ? fmt::format("no convergence in {} Newton iterations", opt.max_newton_iterations)
                : flag == KIN_LINESEARCH_NONCONV ? "the line search found no decrease"
                                                 : fmt::format("KINSOL stopped (flag {}, |R| = {:.3g})", flag, fnorm);
  if (ok) {
    a.record.residual_norms.push_back(fnorm);
    a.record.active_set_sizes.push_back(a.problem.active_set_size(a.t, x_new));
    x = x_new;
  }
  return ok;
}

// Euler (tangent) predictor from the converged state x at t to t + dt:
// x - J(x, t)^{-1} dR/dt dt, with dR/dt by a forward difference in t (the
// ramped loads, prescribed displacements and obstacle motions all enter R
// through t).  Without a history to extrapolate, this is what keeps a first
// step of prescribed displacement from inverting the elements next to the
// moved face.  Nothing (nullopt) when a state is inadmissible (false or a
// NumericalFailure) or the matrix singular; anything else thrown propagates.
std::optional<Eigen::VectorXd> tangent_predictor(NonlinearProblem& problem, const Eigen::VectorXd& x, double t, double dt,
                                                 BlockJacobian& J, LinearBackend& solver) {
  try {
    Eigen::VectorXd r0, r1;
    const double eps = 1e-6 * std::max(dt, 1e-3);
    if (!problem.residual(t, x, r0) || !problem.residual(t + eps, x, r1)) return std::nullopt;
    if (!problem.block_jacobian(t, x, J)) return std::nullopt;
    if (!solver.setup(J)) return std::nullopt;
    Eigen::VectorXd dx;
    if (!solver.solve(Eigen::VectorXd((r1 - r0) * (-dt / eps)), dx, 1e-8)) return std::nullopt;
    return Eigen::VectorXd(x + dx);
  } catch (const NumericalFailure&) {
    return std::nullopt;
  }
}

}  // namespace

LoadSteppingSummary run_load_steps(NonlinearProblem& problem, Eigen::VectorXd& x, const LoadSteppingOptions& opt,
                                   const std::function<void(const LoadStepRecord&, const Eigen::VectorXd&)>& on_step) {
  LoadSteppingSummary summary;
  const Stopwatch clock;
  const ContextOwner context;  // freed also when an error propagates
  const SUNContext ctx = context.ctx;
  BlockJacobian J;
  // one backend for the whole run: the symbolic analysis is kept
  SaddleSolver direct;
  LinearBackend& solver = opt.linear_backend ? *opt.linear_backend : direct;

  double t = 0;
  double dt = opt.first_increment > 0 ? opt.first_increment : 1.0 / std::max(opt.steps, 1);
  Eigen::VectorXd x_old = x;
  double dt_old = 0;
  int cut_backs = 0;
  if (opt.start) {
    t = opt.start->t;
    dt = opt.start->dt;
    dt_old = opt.start->dt_old;
    x = opt.start->x;
    x_old = opt.start->x_old;
  }
  int steps_done = opt.steps_done;
  // Without curves the one corner is t = 1 and nothing below differs from
  // a plain ramp to 1 (the same increments, bit for bit); with them a step
  // that reaches a corner ends on it exactly.
  const bool curves = !opt.corners.empty();
  const std::vector<double> corners = curves ? opt.corners : std::vector<double>{1.0};
  size_t next = 0;  // the first corner ahead of t
  while (true) {
    while (next < corners.size() && !(t < corners[next] - 1e-12)) ++next;
    if (next == corners.size()) break;
    if (opt.max_steps > 0 && steps_done >= opt.max_steps) {
      summary.status = RunStatus::stopped_as_asked(steps_done);
      break;
    }
    const double corner = corners[next];
    problem.begin_step(t, x);
    dt = std::min(dt, opt.max_increment);
    const double h = std::min(dt, corner - t);  // this step's increment
    const double t_new = curves && h == corner - t ? corner : t + h;
    bool done = false;
    std::string why;
    // First try from a predicted state: extrapolated from the last
    // increment, or (no history yet) the tangent predictor; then from the
    // last converged state as it is.
    std::optional<Eigen::VectorXd> predicted;
    if (dt_old > 0 && !opt.tangent_every_step) predicted = Eigen::VectorXd(x + (x - x_old) * (h / dt_old));
    else if (opt.tangent_predictor) predicted = tangent_predictor(problem, x, t, h, J, solver);
    for (int attempt = 0; attempt < 2 && !done; ++attempt) {
      if (attempt == 0 && !predicted) continue;
      Eigen::VectorXd x_try = attempt == 0 ? *predicted : x;
      Attempt a{problem, t_new, 1.0, J, solver, summary, {}, {}, {}, {}, false, {}, {}, {}, {}};
      a.record.load_factor = t_new;
      bool ok = solve_step(a, x_try, ctx, opt);
      const int first_solve = a.record.newton_iterations;  // the step's speed, augmentations aside
      // An augmented Lagrangian: while the problem updates its multipliers,
      // the step is solved again from where it stands (Newton iterations summed).
      while (ok && a.problem.augment(t_new, x_try)) {
        if (a.record.augmentations == opt.max_augmentations) {
          ok = false;
          a.failure = fmt::format("the constraint is not met after {} augmentations", opt.max_augmentations);
          break;
        }
        ++a.record.augmentations;
        a.active_history.clear();  // a new solve: the residual changed with the multipliers
        a.x_accepted.resize(0);
        const int before = a.record.newton_iterations;
        ok = solve_step(a, x_try, ctx, opt);
        a.record.newton_iterations += before;
      }
      problem.keep_augmentation(ok);
      if (ok) {
        a.record.cut_backs = cut_backs;
        x_old = x;
        x = x_try;
        dt_old = h;
        t = t_new;
        summary.steps.push_back(a.record);
        ++steps_done;
        // The next step's start: a corner of a curve turns the load, so the
        // next step is predicted by the tangent, not extrapolated from this
        // one, and starts from the increment this one had before it was cut
        // to the corner.
        if (curves && t == corner) dt_old = 0;
        if (!(curves && h < dt)) dt = h;
        if (first_solve <= opt.fast_iterations) dt *= opt.growth;
        if (opt.on_state) opt.on_state({t, dt, dt_old, x, x_old});
        if (!opt.quiet)
          fmt::print(stderr, "step {:3d}: {} {:.4f} (increment {:.3g}), {} Newton iterations, |R|/F {:.2e}, active {}{}{}{}\n",
                     steps_done, curves ? "time" : "load factor", t, h, a.record.newton_iterations,
                     a.record.residual_norms.back(), a.record.active_set_sizes.back(),
                     a.record.augmentations ? fmt::format(", {} augmentation(s)", a.record.augmentations) : "",
                     cut_backs ? fmt::format(", {} cut-back(s)", cut_backs) : "", progress_suffix(t / corners.back()));
        if (on_step) on_step(summary.steps.back(), x);
        cut_backs = 0;
        done = true;
      } else {
        why = a.failure;
      }
    }
    if (done) continue;
    ++cut_backs;
    dt = h * 0.5;
    if (!opt.quiet)
      fmt::print(stderr, "         {} {:.4f} failed ({}): cut back to increment {:.3g}\n", curves ? "time" : "load factor",
                 t + 2 * dt, why, dt);
    if (dt < opt.min_increment) {
      summary.status = RunStatus::failed(fmt::format("stopped at {} {:.6g}: {} even with an increment below {:.3g}",
                                                     curves ? "time" : "load factor", t, why, opt.min_increment));
      summary.unfinished_cut_backs = cut_backs;
      break;
    }
  }
  if (!summary.status.is_set()) summary.status = RunStatus::converged();  // (every corner reached)
  summary.linear = solver.stats();
  if (summary.linear.setups > 0) summary.condition_estimate = solver.condition_estimate();
  summary.newton_seconds = clock.seconds();
  return summary;
}

}  // namespace igac
