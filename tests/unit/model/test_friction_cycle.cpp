// SPDX-License-Identifier: BSD-3-Clause
// Friction along load curves (model/load_history.cpp with
// contact/small_strain_friction): each step starts from the state and slip
// history of the last, so a load that goes up and comes back gives the
// hysteresis friction implies.
//  - Cattaneo-Mindlin cycled (Mindlin-Deresiewicz; cases/cattaneo_mindlin_cycle.toml
//    with one more cycle): the plane moved 0 -> +d -> -d -> +d -> -d -> +d
//    under the pressed half cylinder.  The loop closes (after the first
//    unloading each cycle ends in the same state, to round-off), its area
//    (the energy dissipated per cycle) is positive and what Masing's rule
//    gives from the loading branch, the unloading branch is the loading one
//    scaled by 2 and turned (Masing's rule, Mindlin-Deresiewicz), the stick
//    zone grows again from the edges on unloading; frictionless, or with a
//    friction that never slides (f = 10), the same curve gives no area.
//  - A sliding block dragged and brought back: the tangential force goes
//    from +f N to -f N and the block ends displaced on the plane.
//  - In 3D, a block pressed on a plane that is dragged along (0.6, 0.8)
//    there and back: at each turn every slip direction turns back, the
//    iteration starts again from every multiplier stuck (it did not settle
//    in 100 iterations before), and the force follows the plane's motion.
//  - Without a curve a frictional case runs as before (the golden records).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>
#include <fmt/format.h>

#include "contact/small_strain_friction.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/stick_zone.hpp"

namespace igac {
namespace {
namespace fs = std::filesystem;

const std::string kSourceDir = IGAC_SOURCE_DIR;
constexpr double kF = 0.3;

struct Frame {
  double t = 0, moved = 0, Q = 0, N = 0;
  Eigen::MatrixXd u;
  Eigen::VectorXd lambda, lambda_t, tangential;
  std::vector<char> state;
};

struct Cycle {
  Model model;
  RunResult result;
  std::vector<Frame> frames;
};

Cycle run_cycle(const CaseSpec& spec) {
  Cycle c{build_model(spec), {}, {}};
  c.result = solve_model(c.model, quiet_run([&](const RunResult& step, double t) {
    Frame f;
    f.t = t;
    f.moved = c.model.contacts.front().curve(t) * c.model.contacts.front().motion[0];
    const ObstacleReaction& r = step.reactions.at(0);
    f.N = r.normal_force;
    f.Q = r.tangential_force.size() ? r.tangential_force[0] : 0.0;
    f.tangential = r.tangential_force;
    f.u = step.u;
    f.lambda = step.contact->solution.lambda;
    f.lambda_t = step.contact->solution.lambda_t;
    f.state = step.contact->solution.friction_state;
    c.frames.push_back(std::move(f));
  }));
  return c;
}

const Frame& at(const Cycle& c, double t) {
  for (const Frame& f : c.frames)
    if (std::abs(f.t - t) < 1e-12) return f;
  throw std::runtime_error("no step at that time");
}

// The area of the loop Q(moved) over t in [from, to] (trapezoids): the
// work the plane does on the body over a cycle, what friction dissipates.
double loop_area(const Cycle& c, double from, double to) {
  double area = 0;
  for (size_t i = 1; i < c.frames.size(); ++i)
    if (c.frames[i - 1].t >= from - 1e-12 && c.frames[i].t <= to + 1e-12)
      area += 0.5 * (c.frames[i].Q + c.frames[i - 1].Q) * (c.frames[i].moved - c.frames[i - 1].moved);
  return area;
}

// The shipped cycle, 8 steps per unit of time, on its mesh (128 x 16 per
// patch) or a coarser one; `cycles` 2: one more unloading and reloading
// (to -d at t = 5, +d at t = 6).
CaseSpec cycle_spec(double friction, std::vector<int> elements, int cycles = 1) {
  CaseSpec spec = read_case(kSourceDir + "/cases/cattaneo_mindlin_cycle.toml");
  spec.elements = std::move(elements);
  spec.contacts.at(0).friction = friction;
  if (cycles == 2) spec.contacts.at(0).obstacle.curve =
      LoadCurve(std::vector<std::array<double, 2>>{{0, 0}, {1, 0}, {2, 1}, {3, -1}, {4, 1}, {5, -1}, {6, 1}});
  return spec;
}

void expect_same_state(const Frame& a, const Frame& b, double tol) {
  const double lambda_scale = b.lambda.cwiseAbs().maxCoeff();
  EXPECT_NEAR(a.Q, b.Q, tol * kF * b.N) << "t = " << a.t << " and " << b.t;
  EXPECT_NEAR(a.N, b.N, tol * b.N);
  EXPECT_LE((a.u - b.u).cwiseAbs().maxCoeff(), tol * b.u.cwiseAbs().maxCoeff());
  EXPECT_LE((a.lambda - b.lambda).cwiseAbs().maxCoeff(), tol * lambda_scale);
  EXPECT_LE((a.lambda_t - b.lambda_t).cwiseAbs().maxCoeff(), tol * lambda_scale);
  EXPECT_EQ(a.state, b.state);
}

TEST(FrictionCycle, CattaneoMindlinLoopClosesWithPositiveArea) {
  const Cycle c = run_cycle(cycle_spec(kF, {128, 16}, 2));
  ASSERT_EQ(c.result.status, "converged");
  ASSERT_EQ(c.frames.size(), 48u);  // 8 steps in each unit of time, t = 0 .. 6
  const Frame &peak = at(c, 2.0), &low = at(c, 3.0), &again = at(c, 4.0);
  const double fN = kF * peak.N;
  ASSERT_GT(peak.Q, 0.3 * fN);  // a real tangential load: partial slip
  ASSERT_LT(peak.Q, fN);
  // The loop closes: after the first unloading every cycle is the same, to
  // round-off (the second reloading ends where the first did, the second
  // unloading where the first did).
  expect_same_state(at(c, 6.0), again, 1e-10);
  expect_same_state(at(c, 5.0), low, 1e-10);
  // The first loading started from the press, which left some tangential
  // traction (nu = 0.45, not 0.5): it ends 5.8e-4 of Q from the reloading.
  EXPECT_NEAR(again.Q, peak.Q, 1e-3 * peak.Q);
  // Symmetric: at -d the force is the opposite of the one at +d.
  EXPECT_NEAR(low.Q, -again.Q, 1e-10 * fN);
  // Masing's rule: unloading k steps from +d (by 2k d / 8) has come down
  // by twice what loading k steps (by k d / 8) went up: Q* - Q_u(k) = 2 Q_l(k)
  // (to 6.3e-4 Q* here: the press's traction again).
  double loading_integral = 0;  // of Q_l over the loading, trapezoids
  for (int k = 1; k <= 8; ++k) {
    const Frame &up = at(c, 1 + k / 8.0), &before = at(c, 1 + (k - 1) / 8.0);
    loading_integral += 0.5 * (up.Q + before.Q) * (up.moved - before.moved);
    if (k == 8) continue;
    const Frame& down = at(c, 2 + k / 8.0);
    EXPECT_NEAR(peak.Q - down.Q, 2 * up.Q, 1e-3 * peak.Q) << "k = " << k;
  }
  // Dissipation: the closed loop's area (t = 4 -> 6, or 3 -> 5: the same
  // loop) is positive, and what Masing's rule gives from the first loading
  // branch, 8 (int_0^d Q_l - d Q* / 2), eight times the area between the
  // loading curve and its chord (to 2.0 % here: the loop is thin, 1.4 % of
  // 4 d Q*, and the first loading carries the press's traction).
  const double d = 0.008, area = loop_area(c, 4.0, 6.0), masing = 8 * (loading_integral - d * peak.Q / 2);
  EXPECT_GT(area, 0.01 * 4 * d * peak.Q);
  EXPECT_NEAR(area, masing, 0.03 * masing);
  EXPECT_NEAR(loop_area(c, 3.0, 5.0), area, 1e-9 * area);
  // Unloading: the edges stick again first; a step after the turn the stick
  // zone is larger than at the peak.
  const ContactFace& face = *c.model.contacts.front().face;
  const igac_test::StickZone z_peak = igac_test::stick_zone(face, peak.state);
  const igac_test::StickZone z_turn = igac_test::stick_zone(face, at(c, 2.125).state);
  EXPECT_GT(z_turn.stuck, z_peak.stuck);
  EXPECT_GT(z_turn.half_width, z_peak.half_width);
}

TEST(FrictionCycle, NoAreaWithoutSlip) {
  // Frictionless the plane moves under the body with no force; with f = 10
  // nothing slips, the body is elastic and the path does not matter.
  CaseSpec none_spec = cycle_spec(0.0, {64, 8}), glued_spec = cycle_spec(10.0, {64, 8});
  none_spec.loading.steps = glued_spec.loading.steps = 4;
  const Cycle none = run_cycle(none_spec), glued = run_cycle(glued_spec);
  ASSERT_EQ(none.result.status, "converged");
  ASSERT_EQ(glued.result.status, "converged");
  EXPECT_EQ(loop_area(none, 2.0, 4.0), 0.0);
  const Frame& peak = at(glued, 2.0);
  EXPECT_GT(peak.Q, 0.0);
  EXPECT_NEAR(loop_area(glued, 2.0, 4.0), 0.0, 1e-10 * 4 * 0.008 * peak.Q);
  EXPECT_NEAR(at(glued, 3.0).Q, -peak.Q, 1e-10 * peak.Q);
}

// The block of tests/unit/model/test_friction.cpp (1 x 0.25, E = 1, nu = 0,
// top held in x, pressed by 0.01) with its plane moved by a curve: 0 over
// the press (t = 0 -> 1), to +delta (t = 2), back to 0 (t = 3).  delta =
// 0.01 is past the shear at f N (1.5e-3): it slides each way.
fs::path block_cycle_case(double friction) {
  const fs::path dir = fs::temp_directory_path() / "igac_friction_cycle";
  fs::create_directories(dir);
  const fs::path path = dir / fmt::format("block_{}.toml", friction);
  std::ofstream(path) << "[geometry]\nshape = \"rectangle\"\nsize = [1.0, 0.25]\n"
                         "[mesh]\ndegree = 2\nelements = [16, 4]\n"
                         "[material]\nE = 1.0\nnu = 0.0\n"
                         "[[dirichlet]]\nfaces = [\"top\"]\ncomponent = \"x\"\n"
                         "[[pressure]]\nfaces = [\"top\"]\nvalue = 0.01\n"
                         "[contact]\nface = \"bottom\"\nfriction = "
                      << friction
                      << "\n[contact.obstacle]\ntype = \"plane\"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]\n"
                         "motion = [0.01, 0.0]\ncurve = [[0, 0], [1, 0], [2, 1], [3, 0]]\n"
                         "[loading]\nsteps = 4\n";
  return path;
}

TEST(FrictionCycle, SlidingBlockDraggedAndBroughtBackEndsDisplaced) {
  const Cycle c = run_cycle(read_case(block_cycle_case(kF).string()));
  ASSERT_EQ(c.result.status, "converged");
  const double N = 0.01, fN = kF * N, tol = 1e-11 * fN;  // P x width 1
  const Frame &pressed = at(c, 1.0), &there = at(c, 2.0), &back = at(c, 3.0);
  EXPECT_NEAR(pressed.N, N, 1e-11 * N);
  EXPECT_NEAR(pressed.Q, 0.0, tol);  // nu = 0: the press alone needs no friction
  EXPECT_NEAR(there.Q, fN, tol);     // dragged along +x: sliding
  EXPECT_NEAR(back.Q, -fN, tol);     // brought back: sliding the other way
  for (const Frame& f : c.frames) EXPECT_LE(std::abs(f.Q), fN + tol);
  // The plane is back at its start, the block is not: it slid on the plane
  // there and back, and its bottom stays displaced along -x, held there by
  // the force -f N (the block's shear at f N: 1.5e-3 from the middle of the
  // block's height, its bottom control points' mean -2.0e-3).
  const Eigen::MatrixXd& u = back.u;
  double bottom_x = 0;
  int n = 0;
  for (const ContactSide& side : c.model.contacts.front().face->sides)
    for (int a : c.model.body.side_control_points(side.side)) bottom_x += u(a, 0), ++n;
  bottom_x /= n;
  EXPECT_LT(bottom_x, -1e-3);
  const Eigen::VectorXd& slip = c.result.contact->solution.slip;  // accumulated, each way
  EXPECT_GT(slip.cwiseAbs().minCoeff(), 1e-3);
  // Frictionless the same curve leaves it where it started, with no force.
  const Cycle free = run_cycle(read_case(block_cycle_case(0.0).string()));
  ASSERT_EQ(free.result.status, "converged");
  for (const Frame& f : free.frames) EXPECT_EQ(f.Q, 0.0);
}

// Between two bodies (the blocks of tests/unit/model/test_two_body_friction.cpp:
// an upper block pressed by 0.01 on a lower one, f = 0.3): the lower block
// moved with its support by master_motion along master_curve, to +0.02 and
// back to 0.  The tangential force is +f N there and -f N back; the lower
// block's output displacement carries its motion at each step.
TEST(FrictionCycle, TwoBodiesMasterCurveThereAndBack) {
  auto body = [](const char* name, double y0, int nx) {
    return fmt::format("[[body]]\nname = \"{}\"\n[body.geometry]\nshape = \"rectangle\"\nsize = [1.0, 0.25]\n"
                       "translate = [0.0, {}]\n[body.mesh]\ndegree = 2\nelements = [{}, 4]\n[body.material]\nE = 1.0\n"
                       "nu = 0.0\n", name, y0, nx);
  };
  const fs::path dir = fs::temp_directory_path() / "igac_friction_cycle";
  fs::create_directories(dir);
  std::ofstream(dir / "blocks.toml") << body("upper", 0.25, 16) + body("lower", 0.0, 12) +
      "[[dirichlet]]\nfaces = [\"upper:top\"]\ncomponent = \"x\"\n"
      "[[dirichlet]]\nfaces = [\"lower:bottom\"]\ncomponent = \"x\"\n"
      "[[dirichlet]]\nfaces = [\"lower:bottom\"]\ncomponent = \"y\"\n"
      "[[pressure]]\nfaces = [\"upper:top\"]\nvalue = 0.01\n"
      "[[contact]]\nface = \"upper:bottom\"\nmaster = \"lower:top\"\nfriction = 0.3\nmaster_motion = [0.02, 0.0]\n"
      "master_curve = [[0, 0], [1, 0], [2, 1], [3, 0]]\n[loading]\nsteps = 2\n";
  Cycle c{build_model(read_case((dir / "blocks.toml").string())), {}, {}};
  std::vector<double> Q, corner_x;
  const int corner = c.model.body.body_cps(1).front();  // a control point of the lower block
  c.result = solve_model(c.model, quiet_run([&](const RunResult& step, double) {
    Q.push_back(step.reactions.at(0).tangential_force[0]);
    corner_x.push_back(step.u(corner, 0));
  }));
  ASSERT_EQ(c.result.status, "converged");
  ASSERT_EQ(Q.size(), 6u);  // t = 0.5, 1, 1.5, 2, 2.5, 3
  const double fN = kF * 0.01, tol = 1e-11 * fN;
  EXPECT_NEAR(Q[1], 0.0, tol);   // pressed (nu = 0: no friction needed)
  EXPECT_NEAR(Q[3], fN, tol);    // dragged to +0.02: sliding
  EXPECT_NEAR(Q[5], -fN, tol);   // brought back: sliding the other way
  EXPECT_NEAR(corner_x[3], 0.02, 1e-15);  // (the corner on the support: its motion alone)
  EXPECT_NEAR(corner_x[4], 0.01, 1e-15);
  EXPECT_NEAR(corner_x[5], 0.0, 1e-15);
}

// A 3D block (1 x 1 x 0.5, nu = 0.3) clamped at its top, pushed down by
// 0.01 onto a plane, the plane then dragged to +d = (0.01, 0.004) and back
// to -d and +d (Mindlin-Deresiewicz in 3D, past sliding each way).  At each
// turn every sliding multiplier's direction turns back in the first
// iteration: read as the overshoot cycle it is, the iteration starts from
// every multiplier stuck.  Before, the directions flipped back and forth and
// the step at t = 2.25 stopped after 100 iterations.
TEST(FrictionCycle, ABlockDraggedThereAndBackIn3DSettlesAtEachTurn) {
  const fs::path dir = fs::temp_directory_path() / "igac_friction_cycle";
  fs::create_directories(dir);
  std::ofstream(dir / "block3d.toml")
      << "[geometry]\nshape = \"box\"\nsize = [1.0, 1.0, 0.5]\n[mesh]\ndegree = 2\nelements = [8, 8, 4]\n"
         "[material]\nE = 1.0\nnu = 0.3\n"
         "[[dirichlet]]\nfaces = [\"top\"]\ncomponent = \"x\"\n"
         "[[dirichlet]]\nfaces = [\"top\"]\ncomponent = \"y\"\n"
         "[[dirichlet]]\nfaces = [\"top\"]\ncomponent = \"z\"\nvalue = -0.01\n"
         "[contact]\nface = \"bottom\"\nfriction = 0.3\n[contact.obstacle]\ntype = \"plane\"\n"
         "point = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\nmotion = [0.01, 0.004, 0.0]\n"
         "curve = [[0, 0], [1, 0], [2, 1], [3, -1], [4, 1]]\n[loading]\nsteps = 4\n";
  const Cycle c = run_cycle(read_case((dir / "block3d.toml").string()));
  ASSERT_EQ(c.result.status, "converged");
  ASSERT_EQ(c.frames.size(), 16u);
  constexpr double kRoundOff = 1e-11;
  for (const Frame& f : c.frames) {
    const double scale = f.lambda.cwiseAbs().maxCoeff();
    for (size_t K = 0; K < f.state.size(); ++K) {
      const double on_disc = f.lambda_t.segment(2 * Eigen::Index(K), 2).norm(), cone = -kF * f.lambda[Eigen::Index(K)];
      if (f.state[K] == kSlip) EXPECT_NEAR(on_disc, cone, kRoundOff * scale) << "t = " << f.t << ", multiplier " << K;
      if (f.state[K] == kStick) EXPECT_LE(on_disc, cone + kRoundOff * scale) << "t = " << f.t << ", multiplier " << K;
    }
    EXPECT_LE(f.tangential.norm(), kF * f.N * (1 + kRoundOff));
  }
  // The force follows the plane: along +d at +d, along -d at -d.
  const Eigen::Vector2d d = Eigen::Vector2d(0.01, 0.004).normalized();
  const Frame &there = at(c, 2.0), &back = at(c, 3.0), &again = at(c, 4.0);
  EXPECT_GT(there.tangential.dot(d), 0.5 * kF * there.N);
  EXPECT_LT(back.tangential.dot(d), -0.5 * kF * back.N);
  EXPECT_GT(again.tangential.dot(d), 0.5 * kF * again.N);
}

}  // namespace
}  // namespace igac
