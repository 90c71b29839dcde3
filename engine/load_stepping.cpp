// SPDX-License-Identifier: BSD-3-Clause
#include "engine/load_stepping.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <fmt/format.h>
#include <memory>
#include <optional>

#include "engine/numerical_failure.hpp"
#include "engine/progress_bar.hpp"
#include "engine/stopwatch.hpp"

namespace igac {
namespace {

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
  // one backend for the whole run: the symbolic analysis is kept
  SaddleSolver direct;
  LinearBackend& solver = opt.linear_backend ? *opt.linear_backend : direct;
  KinsolNewton newton(problem, solver,
                      {opt.max_newton_iterations, opt.tolerance, opt.line_search, opt.halving_line_search,
                       opt.linearised_active_set});
  BlockJacobian& J = newton.jacobian();

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
      LoadStepRecord record;
      record.load_factor = t_new;
      NewtonRecord path;
      bool ok = newton.solve(t_new, x_try, path);
      std::string failure = newton.failure();
      // From a predicted start Newton must reach the tolerance: a stall
      // between it and the slack KinsolNewton allows (10x, for a stiff
      // case's round-off floor) is solved again from the last solution.
      // Whether such a stall lands inside the slack follows the machine's
      // last digits (cases/oring_on_plate.toml's first step: 5.3e-9 on one
      // process, 7.8e-9 on two), and with it the load path would.
      if (ok && attempt == 0 && !path.residual_norms.empty() && path.residual_norms.back() > opt.tolerance) {
        ok = false;
        failure = fmt::format("stalled at |R|/F {:.2e} from the predicted start", path.residual_norms.back());
      }
      const int first_solve = path.iterations;  // the step's speed, augmentations aside
      int iterations = path.iterations;
      // An augmented Lagrangian: while the problem updates its multipliers,
      // the step is solved again from where it stands (Newton iterations summed).
      while (ok && problem.augment(t_new, x_try)) {
        if (record.augmentations == opt.max_augmentations) {
          ok = false;
          failure = fmt::format("{} after {} augmentations", problem.unsettled_augmentation(), opt.max_augmentations);
          break;
        }
        ++record.augmentations;
        ok = newton.solve(t_new, x_try, path);
        failure = newton.failure();
        iterations += path.iterations;
      }
      record.newton_iterations = iterations;
      record.residual_norms = std::move(path.residual_norms);
      record.active_set_sizes = std::move(path.active_set_sizes);
      problem.keep_augmentation(ok);
      if (ok) {
        record.cut_backs = cut_backs;
        x_old = x;
        x = x_try;
        dt_old = h;
        t = t_new;
        summary.steps.push_back(record);
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
                     steps_done, curves ? "time" : "load factor", t, h, record.newton_iterations,
                     record.residual_norms.back(), record.active_set_sizes.back(),
                     record.augmentations ? fmt::format(", {} augmentation(s)", record.augmentations) : "",
                     cut_backs ? fmt::format(", {} cut-back(s)", cut_backs) : "", progress_suffix(t / corners.back()));
        if (on_step) on_step(summary.steps.back(), x);
        cut_backs = 0;
        done = true;
      } else {
        why = failure;
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
  summary.residual_seconds = newton.residual_seconds();
  summary.jacobian_seconds = newton.jacobian_seconds();
  summary.linear = solver.stats();
  if (summary.linear.setups > 0) summary.condition_estimate = solver.condition_estimate();
  summary.newton_seconds = clock.seconds();
  return summary;
}

}  // namespace igac
