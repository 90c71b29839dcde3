// SPDX-License-Identifier: BSD-3-Clause
// The load-stepping driver (engine/load_stepping.hpp) and exceptions thrown
// inside KINSOL's callbacks: a NumericalFailure fails the step, which is cut
// back; anything else — a bug (std::logic_error, std::out_of_range) — comes
// out of run_load_steps as itself, never as a "failed" status.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>
#include <functional>
#include <stdexcept>

#include "engine/load_stepping.hpp"
#include "engine/numerical_failure.hpp"

using namespace igac;

namespace {

// R(x; t) = x - t, one unknown; on_residual / on_jacobian run before every
// evaluation with its number (from 1) and the load factor, and may throw.
class ScriptedProblem final : public NonlinearProblem {
 public:
  std::function<void(int call, double t)> on_residual = [](int, double) {};
  std::function<void(int call, double t)> on_jacobian = [](int, double) {};
  int size() const override { return 1; }
  bool residual(double t, const Eigen::VectorXd& x, Eigen::VectorXd& r) override {
    on_residual(++residual_calls, t);
    r.resize(1);
    r[0] = x[0] - t;
    return true;
  }
  bool jacobian(double t, const Eigen::VectorXd&, Eigen::SparseMatrix<double>& J) override {
    on_jacobian(++jacobian_calls, t);
    J.resize(1, 1);
    J.coeffRef(0, 0) = 1;
    J.makeCompressed();
    return true;
  }
  double force_scale(double, const Eigen::VectorXd&) override { return 1; }
  int residual_calls = 0, jacobian_calls = 0;
};

LoadSteppingOptions quiet_options() {
  LoadSteppingOptions opt;
  opt.quiet = true;
  opt.steps = 4;
  opt.min_increment = 1e-3;
  return opt;
}

}  // namespace

TEST(LoadStepping, ConvergesOnTheScriptedProblem) {
  ScriptedProblem problem;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  const LoadSteppingSummary s = run_load_steps(problem, x, quiet_options(), {});
  EXPECT_EQ(s.status, "converged");
  EXPECT_NEAR(x[0], 1.0, 1e-12);
}

// A bug in the residual, once the first step has converged: before, the
// barrier around the callbacks made it a failed step, the driver cut back
// until the minimum increment and returned "stopped at load factor 0.25:
// <message>" (exit 1, as if the problem were hard).
TEST(LoadStepping, LogicErrorInResidualPropagates) {
  ScriptedProblem problem;
  bool first_step_done = false;
  problem.on_residual = [&](int, double t) {
    if (t > 0.3) throw std::logic_error("residual: a bug");
  };
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  LoadSteppingSummary s;
  EXPECT_THROW(s = run_load_steps(problem, x, quiet_options(),
                                  [&](const LoadStepRecord&, const Eigen::VectorXd&) { first_step_done = true; }),
               std::logic_error);
  EXPECT_TRUE(first_step_done);
  EXPECT_NEAR(x[0], 0.25, 1e-12) << "x keeps the last converged state";
}

// The type survives the trip through KINSOL's C frames (an exception_ptr,
// not a message), from the Jacobian too (without the tangent predictor, the
// first Jacobian is KINSOL's first Newton iteration).
TEST(LoadStepping, OutOfRangeInJacobianPropagatesAsItself) {
  ScriptedProblem problem;
  problem.on_jacobian = [](int, double) { throw std::out_of_range("jacobian: index 7 of 1"); };
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  LoadSteppingOptions opt = quiet_options();
  opt.tangent_predictor = false;
  try {
    run_load_steps(problem, x, opt, {});
    FAIL() << "run_load_steps returned";
  } catch (const std::out_of_range& e) {
    EXPECT_STREQ(e.what(), "jacobian: index 7 of 1");
  }
}

// The tangent predictor of the first step evaluates the residual outside
// KINSOL: a bug there propagates too (it used to be read as "no predictor").
TEST(LoadStepping, LogicErrorInTangentPredictorPropagates) {
  ScriptedProblem problem;
  problem.on_residual = [](int call, double) {
    if (call == 1) throw std::logic_error("predictor: a bug");
  };
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  EXPECT_THROW(run_load_steps(problem, x, quiet_options(), {}), std::logic_error);
}

// An expected failure: the state cannot be evaluated at the second step's
// load; the step is cut back and the run converges.  (A failure that
// persists ends the run with a status: HostileInput.ExceptionInsideKinsol...)
TEST(LoadStepping, NumericalFailureCutsTheStepBack) {
  ScriptedProblem problem;
  int thrown = 0;
  problem.on_residual = [&](int, double t) {
    if (t > 0.3 && thrown < 2) {  // both attempts of the second step
      ++thrown;
      throw NumericalFailure("no normal there");
    }
  };
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  LoadSteppingSummary s;
  ASSERT_NO_THROW(s = run_load_steps(problem, x, quiet_options(), {}));
  EXPECT_EQ(s.status, "converged");
  EXPECT_GT(thrown, 0);
  int cut_backs = 0;
  for (const auto& step : s.steps) cut_backs += step.cut_backs;
  EXPECT_GT(cut_backs, 0);
  EXPECT_NEAR(x[0], 1.0, 1e-12);
}

// Load curves: with corners at t = 1 and 2 (the scripted R = x - t stands
// for any load) the run goes to 2, every corner is a step's end exactly,
// and a failure inside the second segment is cut back and retried there
// without the steps leaving their segment.
TEST(LoadStepping, StepsEndOnCornersAndCutBackInsideASegment) {
  ScriptedProblem problem;
  int thrown = 0;
  problem.on_residual = [&](int, double t) {
    if (t > 1.5 && thrown < 2) {  // both attempts of the step from 1 to 2
      ++thrown;
      throw NumericalFailure("not there");
    }
  };
  LoadSteppingOptions opt = quiet_options();
  opt.steps = 3;  // increments of 1/3, growing: a step would straddle t = 1 without the corner
  opt.corners = {1.0, 2.0};
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  std::vector<double> times;
  const LoadSteppingSummary s =
      run_load_steps(problem, x, opt, [&](const LoadStepRecord& r, const Eigen::VectorXd&) { times.push_back(r.load_factor); });
  EXPECT_EQ(s.status, "converged");
  EXPECT_EQ(thrown, 2);
  int cut_backs = 0;
  for (const auto& step : s.steps) cut_backs += step.cut_backs;
  EXPECT_GT(cut_backs, 0);
  ASSERT_FALSE(times.empty());
  EXPECT_NE(std::find(times.begin(), times.end(), 1.0), times.end()) << "a step ends on the corner t = 1";
  EXPECT_EQ(times.back(), 2.0);
  for (size_t i = 1; i < times.size(); ++i) EXPECT_GT(times[i], times[i - 1]);
  EXPECT_NEAR(x[0], 2.0, 1e-12);
}

namespace {

// One unknown: R(x; t) = f(t, x) with dR/dx = df(t, x); f returns false
// for an inadmissible state (as det F <= 0 is).
class ScalarProblem final : public NonlinearProblem {
 public:
  std::function<bool(double t, double x, double& r)> f;
  std::function<double(double t, double x)> df;
  int size() const override { return 1; }
  bool residual(double t, const Eigen::VectorXd& x, Eigen::VectorXd& r) override {
    r.resize(1);
    return f(t, x[0], r[0]);
  }
  bool jacobian(double t, const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& J) override {
    J.resize(1, 1);
    J.coeffRef(0, 0) = df(t, x[0]);
    J.makeCompressed();
    return true;
  }
  double force_scale(double, const Eigen::VectorXd&) override { return 1; }
};

// R(x; t) = atan(x - 3 t), solution x = 3 t.  From x = 0 to t = 1 the full
// Newton step overshoots to 12.5 and the next to -120 (KINSOL caps a step
// at 1000 |x_0|, at least 1; the halving search lifts the cap).
// Inadmissible beyond |x| = 50.
ScalarProblem arctan_problem() {
  ScalarProblem p;
  p.f = [](double t, double x, double& r) {
    r = std::atan(x - 3 * t);
    return std::abs(x) <= 50;
  };
  p.df = [](double t, double x) { return 1 / (1 + (x - 3 * t) * (x - 3 * t)); };
  return p;
}

LoadSteppingOptions one_step_from_rest() {
  LoadSteppingOptions opt = quiet_options();
  opt.steps = 1;
  opt.tangent_predictor = false;
  opt.min_increment = 0.9;  // no cut-back: the attempt itself must converge
  return opt;
}

}  // namespace

// The halving line search: where the full Newton step overshoots it
// converges, every accepted step decreasing |R| (Armijo), to the solution.
// The first step: d = atan(3) (1 + 9) = 12.49; s = 1 and 1/2 raise |R|
// (atan(9.49), atan(3.24) > atan(3)), s = 1/4 lowers it: x = 3.1226.
TEST(LoadStepping, HalvingLineSearchConvergesWhereTheFullStepOvershoots) {
  ScalarProblem problem = arctan_problem();
  LoadSteppingOptions halving = one_step_from_rest();
  halving.halving_line_search = true;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  const LoadSteppingSummary s = run_load_steps(problem, x, halving, {});
  ASSERT_EQ(s.status, "converged");
  ASSERT_EQ(s.steps.size(), 1u);
  EXPECT_NEAR(x[0], 3.0, 1e-9);
  const std::vector<double>& r = s.steps[0].residual_norms;
  ASSERT_GE(r.size(), 3u);
  for (size_t k = 1; k < r.size(); ++k) EXPECT_LT(r[k], r[k - 1]) << "iteration " << k;
  EXPECT_NEAR(r[0], std::atan(3.0), 1e-15);
  EXPECT_NEAR(r[1], std::abs(std::atan(0.25 * 10 * std::atan(3.0) - 3)), 1e-14) << "s = 1/4 at the first iteration";
}

// The search says why when no step length decreases |R|: a residual that
// only grows along the Newton step (a wrong Jacobian sign, as a bug would
// give); the run stops there (no increment small enough helps).
TEST(LoadStepping, HalvingLineSearchFailsWithAReason) {
  ScalarProblem problem;
  problem.f = [](double t, double x, double& r) {
    r = x - t;
    return true;
  };
  problem.df = [](double, double) { return -1.0; };
  LoadSteppingOptions opt = one_step_from_rest();
  opt.halving_line_search = true;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  const LoadSteppingSummary s = run_load_steps(problem, x, opt, {});
  EXPECT_NE(s.status.text().find("the line search found no decrease"), std::string::npos) << s.status;
  EXPECT_EQ(x[0], 0.0) << "x keeps the last converged state";
}

// tangent_every_step on R(x; t) = x - t^2 (linear in x: a step's first
// residual is what its predictor missed by): the second step starts from
// x - J^{-1} dR/dt h, off by h^2 = 0.25 from t^2 (a forward difference in t
// adds 1e-6 h), not from the last increment extrapolated, off by 2 h^2 = 0.5.
TEST(LoadStepping, TangentPredictorAtEveryStep) {
  ScalarProblem problem;
  problem.f = [](double t, double x, double& r) {
    r = x - t * t;
    return true;
  };
  problem.df = [](double, double) { return 1.0; };
  LoadSteppingOptions opt = quiet_options();
  opt.steps = 2;
  for (const bool every : {false, true}) {
    opt.tangent_every_step = every;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
    const LoadSteppingSummary s = run_load_steps(problem, x, opt, {});
    ASSERT_EQ(s.status, "converged");
    ASSERT_EQ(s.steps.size(), 2u);
    EXPECT_NEAR(s.steps[1].residual_norms.front(), every ? 0.25 : 0.5, 1e-5) << "tangent_every_step " << every;
    EXPECT_NEAR(x[0], 1.0, 1e-12);
  }
}

// A stall from the predicted start is not a converged step.  R = x - t +
// 5e-9: the solution is x = t - 5e-9.  At t > 0 within 1e-6 of x = t the
// problem's Jacobian reads 1e10 (wrong: a round-off floor the steps cannot
// get under), so Newton from the tangent predictor (x = t exactly, |R| =
// 5e-9, between the tolerance 1e-9 and the 10x slack) takes steps of
// 5e-19 and KINSOL stops on its step tolerance.  That attempt is solved
// again from the last solution, x = 0, whose Jacobian is right: one Newton
// step to the solution.  Accepting the stall would end the step at x = t.
TEST(LoadStepping, AStallFromThePredictedStartIsSolvedAgainFromTheLastSolution) {
  ScalarProblem problem;
  problem.f = [](double t, double x, double& r) {
    r = x - t + 5e-9;
    return true;
  };
  problem.df = [](double t, double x) { return t > 0 && std::abs(x - t) < 1e-6 ? 1e10 : 1.0; };
  LoadSteppingOptions opt = quiet_options();
  opt.steps = 1;
  opt.line_search = false;
  ASSERT_TRUE(opt.tangent_predictor);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  const LoadSteppingSummary s = run_load_steps(problem, x, opt, {});
  ASSERT_EQ(s.status, "converged");
  ASSERT_EQ(s.steps.size(), 1u);
  EXPECT_NEAR(s.steps[0].residual_norms.front(), 1.0, 1e-8);  // the attempt from x = 0 at t = 1
  EXPECT_LE(s.steps[0].residual_norms.back(), opt.tolerance);
  EXPECT_NEAR(x[0], 1.0 - 5e-9, 1e-15);
}
