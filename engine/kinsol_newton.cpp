// SPDX-License-Identifier: BSD-3-Clause
#include "engine/kinsol_newton.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <fmt/format.h>
#include <memory>
#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include "engine/numerical_failure.hpp"
#include "engine/stopwatch.hpp"

namespace igac {
namespace {

// Everything one KINSOL solve works with.
struct Attempt {
  NonlinearProblem& problem;
  double t = 0;
  double scale = 1;  // force scale: residuals are relative to it
  BlockJacobian& J;
  LinearBackend& solver;
  double& residual_seconds;  // the time spent in callbacks, accumulated
  double& jacobian_seconds;
  NewtonRecord record;
  std::vector<std::vector<char>> active_history;
  std::string failure;        // why the attempt failed (an expected, numerical reason)
  std::exception_ptr error;   // anything else thrown in a callback: rethrown once KINSOL returns
  // The halving line search (LoadSteppingOptions::halving_line_search):
  // KINSOL runs plain Newton and the linear solve returns the step the
  // search accepted, from the state of the last Jacobian; its residual is
  // kept for KINSOL's evaluation at the same state, which follows.
  bool halving = false;
  bool linearised_active_set = true;  // (KinsolNewton::Options)
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
  a.residual_seconds += clock.seconds();
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
  a.record.active_set_sizes.push_back(a.problem.active_set_size(a.t, x));
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
  a.jacobian_seconds += clock.seconds();
  if (!ok) {
    a.failure = "inadmissible state in the Jacobian";
    return -1;
  }
  return 0;
}

// A linear solver for KINSOL: the LinearBackend on the Jacobian blocks the
// problem assembled (the SUNMatrix handed around is an empty placeholder).
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
    a.residual_seconds += clock.seconds();
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
  // 0.01 |R|/F of |R| leaves the next residual ~ |R|^2, Newton stays
  // quadratic, and the last residual lands well below the convergence test
  // rather than on it (with 0.1 an iterative backend's step count drifted
  // from the direct one's when a step ended near the test).
  const double tolerance = std::min(1e-3, 0.01 * rhs.cwiseAbs().maxCoeff() / a.scale);
  Eigen::VectorXd sol;
  if (!a.solver.solve(rhs, sol, tolerance)) {
    a.failure = a.solver.why();
    return -1;
  }
  // The linearised contact problem solved to its own active set (an inner
  // primal-dual active-set loop, NonlinearProblem::relinearise_active_set):
  // started from an overestimated set, the semismooth step peels the
  // contact zone a ring per Newton iteration; here each ring costs a Schur
  // complement, not an evaluation and a factorisation.  The problem ends
  // the loop (a settled set, or one it has tried: a cycle), or kMaxPasses.
  // Only from a state within the force scale (|R|/F < 1): further out (a
  // prescribed displacement's extrapolated start) the linearisation says
  // little about the set, and the semismooth step alone is the safer guide.
  constexpr int kMaxPasses = 50;
  const int passes = a.linearised_active_set && a.relative(rhs) < 1 ? kMaxPasses : 0;
  Eigen::VectorXd moved = rhs;
  for (int pass = 0; pass < passes && a.problem.relinearise_active_set(sol, a.J, moved); ++pass) {
    Eigen::VectorXd next;
    if (!a.solver.update_constraint_rows(a.J) || !a.solver.solve(moved, next, tolerance)) {
      a.failure = a.solver.why();
      return -1;
    }
    sol = std::move(next);
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

// One Newton solve from x at t; x is updated on success.
bool solve_step(Attempt& a, Eigen::VectorXd& x, SUNContext ctx, const KinsolNewton::Options& opt) {
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
  KINSetNumMaxIters(kin, opt.max_iterations);
  KINSetFuncNormTol(kin, opt.tolerance);
  KINSetScaledStepTol(kin, 1e-15);
  a.halving = opt.halving_line_search;
  a.linearised_active_set = opt.linearised_active_set;
  if (a.halving) KINSetMaxNewtonStep(kin, 1e300);  // the search shortens the step, KINSOL must not
  const int flag = KINSol(kin, u, opt.line_search && !a.halving ? KIN_LINESEARCH : KIN_NONE, us, fs);
  if (a.error) std::rethrow_exception(a.error);  // the SUNDIALS objects are freed on the way out
  long iterations = 0;
  KINGetNumNonlinSolvIters(kin, &iterations);
  double fnorm = NAN;
  KINGetFuncNorm(kin, &fnorm);
  const Eigen::VectorXd x_new = view(u);
  a.record.iterations = int(iterations);
  const bool ok = flag >= 0 && std::isfinite(fnorm) && fnorm <= 10 * opt.tolerance && x_new.allFinite();
  if (!ok && a.failure.empty())
    a.failure = flag == KIN_MAXITER_REACHED ? fmt::format("no convergence in {} Newton iterations", opt.max_iterations)
                : flag == KIN_LINESEARCH_NONCONV ? "the line search found no decrease"
                                                 : fmt::format("KINSOL stopped (flag {}, |R| = {:.3g})", flag, fnorm);
  if (ok) {
    a.record.residual_norms.push_back(fnorm);
    a.record.active_set_sizes.push_back(a.problem.active_set_size(a.t, x_new));
    x = x_new;
  }
  return ok;
}

}  // namespace

struct KinsolNewton::Context {
  ContextOwner owner;
};

KinsolNewton::KinsolNewton(NonlinearProblem& problem, LinearBackend& solver, Options options)
    : problem_(problem), solver_(solver), options_(options), context_(std::make_unique<Context>()) {}

KinsolNewton::~KinsolNewton() = default;

bool KinsolNewton::solve(double t, Eigen::VectorXd& x, NewtonRecord& record) {
  Attempt a{problem_, t, 1.0, J_, solver_, residual_seconds_, jacobian_seconds_, {}, {}, {}, {}, false, {}, {}, {}, {}};
  const bool ok = solve_step(a, x, context_->owner.ctx, options_);
  failure_ = a.failure;
  record.iterations = a.record.iterations;
  record.residual_norms.insert(record.residual_norms.end(), a.record.residual_norms.begin(),
                               a.record.residual_norms.end());
  record.active_set_sizes.insert(record.active_set_sizes.end(), a.record.active_set_sizes.begin(),
                                 a.record.active_set_sizes.end());
  return ok;
}

}  // namespace igac
