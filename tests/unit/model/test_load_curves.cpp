// SPDX-License-Identifier: BSD-3-Clause
// Load curves (engine/load_curve.hpp, model/load_history.hpp): the curve
// itself, steps on its corners, and the three paths along a curve that
// unloads -- linear elasticity (the solution is linear in the load: half
// the load, half the displacement, to round-off), large deformation (back
// to zero load, back to zero displacement to the Newton tolerance) and
// small-deformation contact (unloaded, the contact opens).
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <string>

#include "engine/load_curve.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

// A step the observer saw: its time and its displacement.
struct Frame {
  double t;
  Eigen::MatrixXd u;
  int active = -1;  // active multipliers (-1: no contact)
  double contact_force = 0;
};

struct History {
  RunResult result;
  std::vector<Frame> frames;
};

History run(Model& m) {
  History h;
  h.result = solve_model(m, quiet_run([&](const RunResult& step, double t) {
    Frame f{t, step.u};
    if (step.contact) {
      f.active = int(std::count(step.contact->solution.active.begin(), step.contact->solution.active.end(), 1));
      f.contact_force = step.contacts.front().report.total_force;
    }
    h.frames.push_back(std::move(f));
  }));
  return h;
}

History run_text(const std::string& text) {
  Model m = build_model(read_case_text(text, "curve_case.toml"));
  return run(m);
}

const Frame& at(const History& h, double t) {
  for (const Frame& f : h.frames)
    if (f.t == t) return f;
  throw std::runtime_error("no step ends at t = " + std::to_string(t));
}

TEST(LoadCurve, InterpolatesHoldsAndIsTheRampWithoutPoints) {
  const LoadCurve c(std::vector<std::array<double, 2>>{{0, 0}, {1, 1}, {3, 0.5}});
  EXPECT_EQ(c(0.0), 0.0);
  EXPECT_EQ(c(1.0), 1.0);
  EXPECT_EQ(c(3.0), 0.5);  // the corners exactly
  EXPECT_DOUBLE_EQ(c(2.0), 0.75);
  EXPECT_EQ(c(5.0), 0.5);  // held after the last point
  const LoadCurve ramp;
  for (double t : {0.0, 0.1, 0.3, 0.7, 1.0}) EXPECT_EQ(ramp(t), t);
  const LoadCurve hold = LoadCurve::ramp_and_hold();
  for (double t : {0.0, 0.1, 0.3, 0.7, 1.0}) EXPECT_EQ(hold(t), t);  // the same factor as the ramp up to 1
  EXPECT_EQ(hold(2.5), 1.0);
}

TEST(LoadCurve, StepsEndOnEveryCorner) {
  const LoadCurve a(std::vector<std::array<double, 2>>{{0, 0}, {1, 1}, {2, 0}});
  const LoadCurve b(std::vector<std::array<double, 2>>{{0, 0}, {0.3, 1}, {2, 1}});
  const std::vector<double> corners = curve_corners({&a, &b});
  EXPECT_EQ(corners, (std::vector<double>{0.3, 1, 2}));
  const std::vector<double> t = step_times(corners, 4);
  // [0, 0.3]: 2 steps, [0.3, 1]: 3, [1, 2]: 4
  ASSERT_EQ(t.size(), 9u);
  for (double c : corners) EXPECT_NE(std::find(t.begin(), t.end(), c), t.end()) << c;
  EXPECT_TRUE(std::is_sorted(t.begin(), t.end()));
}

// Issue 35: 3e9 steps in one segment overflowed an int (the segment was
// done in one step) and 2e9 step times were allocated before anything
// said no.  Counted in double, refused beyond kMaxLoadSteps.
TEST(LoadCurve, StepCountBeyondTheBoundIsRefusedNotWrapped) {
  EXPECT_EQ(count_step_times({0.3, 1, 2}, 4), 9.0);
  EXPECT_EQ(count_step_times({3e9}, 1), 3e9);
  EXPECT_EQ(segment_steps(0, 3e9, 1), 3e9);
  EXPECT_THROW(step_times({3e9}, 1), std::length_error);
  EXPECT_THROW(step_times({1, 2e6}, 1000), std::length_error);
  EXPECT_EQ(step_times({kMaxLoadSteps}, 1).size(), size_t(kMaxLoadSteps));  // the bound itself runs
}

// A block [0, 2] x [0, 1] held at its left face, pulled by a pressure on
// its right face.  `material` and `extra` complete it.
std::string block(const std::string& material, const std::string& curve, const std::string& extra = "") {
  return R"(
name = "curve_block"
[geometry]
shape = "rectangle"
size = [2.0, 1.0]
[mesh]
degree = 2
elements = [4, 2]
[material]
)" + material + R"(
[[dirichlet]]
faces = ["left"]
component = "x"
[[dirichlet]]
faces = ["bottom"]
component = "y"
[[pressure]]
faces = ["right"]
value = -0.05
curve = )" + curve + "\n" + extra + "\n[output]\nvtk = false\n";
}

// Linear elasticity, curve 0 -> 1 -> 0.5: u(2) = u(1) / 2 to round-off.
TEST(LoadCurves, LinearElasticHalfTheLoadIsHalfTheDisplacement) {
  const History h = run_text(block("model = \"linear_elastic\"\nE = 1.0\nnu = 0.3",
                                   "[[0, 0], [1, 1], [2, 0.5]]", "[loading]\nsteps = 4"));
  ASSERT_EQ(h.result.status, "converged");
  ASSERT_EQ(h.frames.size(), 8u);  // 4 steps per unit of time, on both corners
  const Eigen::MatrixXd& u1 = at(h, 1.0).u;
  const Eigen::MatrixXd& u2 = at(h, 2.0).u;
  ASSERT_GT(u1.norm(), 1e-3);
  // (an exact factor of 1/2 on the load: the solve scales exactly)
  constexpr double kRoundOff = 1e-14;
  EXPECT_LE((u2 - 0.5 * u1).cwiseAbs().maxCoeff(), kRoundOff * u1.cwiseAbs().maxCoeff());
  // the run's state is the last step's, its reactions balance half the load
  EXPECT_EQ(h.result.u, u2);
  ASSERT_EQ(h.result.load_curve.size(), 8u);
  EXPECT_EQ(h.result.load_curve.back().load_factor, 2.0);
  double rx = 0;
  for (const FaceReaction& f : h.result.dirichlet_reactions)
    if (f.face == "left") rx = f.force[0];
  EXPECT_NEAR(rx, -0.5 * 0.05 * 1.0, 1e-12);  // the support holds half of P times the face's length
}

// Large deformation (Neo-Hookean) loaded and unloaded to 0: back to u = 0
// to the Newton tolerance; the steps end on the corner.
TEST(LoadCurves, LargeDeformationUnloadedReturnsToZero) {
  const History h = run_text(block("model = \"neo_hookean\"\nE = 1.0\nnu = 0.3", "[[0, 0], [1, 1], [2, 0]]",
                                   "[loading]\nsteps = 4"));
  ASSERT_EQ(h.result.status, "converged");
  const double u_max = at(h, 1.0).u.cwiseAbs().maxCoeff();
  ASSERT_GT(u_max, 1e-2);
  EXPECT_EQ(h.frames.back().t, 2.0);
  // Newton stops at |R| <= 1e-9 of the force scale; the displacement that
  // leaves is of the order of that times the compliance (E = 1).
  constexpr double kNewtonTolerance = 1e-8;
  EXPECT_LE(h.result.u.cwiseAbs().maxCoeff(), kNewtonTolerance * u_max);
  // The steps up and down: t increases, and none straddles the corner.
  for (size_t i = 1; i < h.frames.size(); ++i) EXPECT_GT(h.frames[i].t, h.frames[i - 1].t);
  ASSERT_EQ(h.result.load_curve.size(), h.frames.size());
  EXPECT_EQ(h.result.load_curve.back().load_factor, 2.0);
}

// Small-deformation contact: the quarter disc of hertz2d over a plane 0.01
// below it, its top face pushed down by 0.05 and back: at the load's peak
// the disc presses on the plane, unloaded the gap is open again and no
// multiplier is active (the active set is decided anew at every step).
TEST(LoadCurves, SmallStrainContactUnloadedReleases) {
  Model m = build_model(read_case(std::string(IGAC_SOURCE_DIR) + "/tests/data/curve_contact.toml"));
  const History h = run(m);

  ASSERT_EQ(h.result.status, "converged");
  const Frame& peak = at(h, 1.0);
  EXPECT_GT(peak.active, 0);
  EXPECT_GT(peak.contact_force, 0.0);
  const Frame& end = at(h, 2.0);
  EXPECT_EQ(end.active, 0);
  EXPECT_EQ(end.contact_force, 0.0);
  EXPECT_EQ(end.u.cwiseAbs().maxCoeff(), 0.0);  // no load, no contact: u = 0 exactly
  EXPECT_EQ(h.result.contacts.front().report.total_force, 0.0);
}

// What curves do not run with, and a curve on a motion that is not there:
// an InputError naming the key (the command line makes it one line, exit 2:
// tests/cli/test_bad_input.cpp).
TEST(LoadCurves, RefusedWhereTheyDoNotApply) {
  const std::string base = block("model = \"linear_elastic\"\nE = 1.0\nnu = 0.3", "[[0, 0], [1, 1]]");
  auto message = [](const std::string& text) {
    try {
      read_case_text(text, "curve_case.toml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string obstacle = R"(
[contact]
face = "bottom"
[contact.obstacle]
type = "plane"
point = [0.0, -0.1]
normal = [0.0, 1.0]
)";
  EXPECT_NE(message(base + obstacle + "curve = [[0, 0], [1, 1]]\n").find("[contact.obstacle] curve: the obstacle has no motion"),
            std::string::npos);
  const std::string with_friction = std::regex_replace(obstacle, std::regex("face = \"bottom\""),
                                                      "face = \"bottom\"\nfriction = 0.3");
  EXPECT_EQ(message(base + with_friction), "accepted");  // (friction runs along curves: tests/unit/model/test_friction_cycle.cpp)
  EXPECT_NE(message(base + "[reference]\nsolution = \"lame\"\n").find("[reference] solution"), std::string::npos);
  EXPECT_EQ(message(base), "accepted");
}

}  // namespace
}  // namespace igac
