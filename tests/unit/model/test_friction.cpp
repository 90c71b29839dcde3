// SPDX-License-Identifier: BSD-3-Clause
// Small-deformation Coulomb friction against a rigid plane
// (contact/small_strain_friction.hpp):
//  - friction = 0 is the frictionless solve, bit for bit;
//  - a sliding block: a block pressed on a plane (nu = 0: no Poisson
//    expansion, so no friction while it is pressed), its top held in x,
//    the plane then moved along x: while everything slides the tangential
//    force is f times the normal force to round-off; a motion far below the
//    elastic shear of the block leaves the pressed multipliers stuck, their
//    slip zero to round-off, and the force below f N;
//  - Cattaneo-Mindlin (cases/cattaneo_mindlin.toml): a half cylinder clamped
//    at its top, pressed on the plane, the plane then moved: the stick zone's
//    half width is c = a sqrt(1 - Q / (f N)) within one multiplier spacing,
//    with N, Q the computed forces and a Hertz's half width for N.
//  - bad friction values: one line naming the key.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "contact/small_strain_friction.hpp"
#include "engine/assembly.hpp"
#include "engine/linear_static.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/stick_zone.hpp"

namespace igac {
namespace {
namespace fs = std::filesystem;

const std::string kSourceDir = IGAC_SOURCE_DIR;
constexpr double kF = 0.3;
// Round-off of the solve relative to the force or the motion.
constexpr double kRoundOff = 1e-11;

struct FrictionRun {
  Model model;
  RunResult result;
};

FrictionRun run_spec(CaseSpec spec) {
  FrictionRun run{build_model(spec), {}};
  run.result = solve_model(run.model, quiet_run());
  return run;
}

fs::path write_case(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "igac_friction";
  fs::create_directories(dir);
  std::ofstream(dir / (name + ".toml")) << text;
  return dir / (name + ".toml");
}

std::string block_case(double friction, double motion, int steps) {
  return "[geometry]\nshape = \"rectangle\"\nsize = [1.0, 0.25]\n"
         "[mesh]\ndegree = 2\nelements = [16, 4]\n"
         "[material]\nE = 1.0\nnu = 0.0\n"
         "[[dirichlet]]\nfaces = [\"top\"]\ncomponent = \"x\"\n"
         "[[pressure]]\nfaces = [\"top\"]\nvalue = 0.01\n"
         "[contact]\nface = \"bottom\"\nfriction = " +
         std::to_string(friction) +
         "\n[contact.obstacle]\ntype = \"plane\"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]\nmotion = [" +
         std::to_string(motion) + ", 0.0]\n" + (friction > 0 ? "[loading]\nsteps = " + std::to_string(steps) + "\n" : "");
}

// How many multipliers stick; each of them has not slipped (to round-off
// of the displacements).
int stuck_without_slip(const FrictionRun& run) {
  return igac_test::stuck_without_slip(run.result.contact->solution, kRoundOff * run.result.u.cwiseAbs().maxCoeff());
}

TEST(Friction, ZeroIsTheFrictionlessSolveBitForBit) {
  CaseSpec plain = read_case(kSourceDir + "/cases/hertz2d.toml");
  CaseSpec zero = plain;
  zero.contacts[0].friction = 0.0;
  const FrictionRun a = run_spec(plain), b = run_spec(zero);
  ASSERT_EQ(a.result.status, "converged");
  EXPECT_EQ(a.result.contact->solution.lambda, b.result.contact->solution.lambda);
  EXPECT_EQ(a.result.u, b.result.u);
  EXPECT_EQ(b.result.contact->solution.lambda_t.size(), 0);
}

TEST(Friction, SlidingBlockForceIsFTimesNormalForce) {
  const FrictionRun run = run_spec(read_case(write_case("slide", block_case(kF, 0.05, 4)).string()));
  ASSERT_EQ(run.result.status, "converged");
  const ContactSolution& s = run.result.contact->solution;
  int sliding = 0;
  for (size_t K = 0; K < s.friction_state.size(); ++K) {
    EXPECT_NE(s.friction_state[K], kStick) << "multiplier " << K;
    sliding += s.friction_state[K] == kSlip;
  }
  EXPECT_EQ(sliding, int(s.friction_state.size()));  // the whole face is pressed, and slides
  const ObstacleReaction& r = run.result.reactions.at(0);
  ASSERT_EQ(r.tangential_force.size(), 1);
  EXPECT_NEAR(r.normal_force, 0.01, kRoundOff * 0.01);  // P x width 1
  // The plane drags the block along +x.
  EXPECT_NEAR(r.tangential_force[0], kF * r.normal_force, kRoundOff * r.normal_force);
}

TEST(Friction, BlockBelowSlidingSticks) {
  const double motion = 1e-6;  // the shear of the block at f N is 0.3 * 0.01 * 0.25 / G = 1.5e-3
  const FrictionRun run = run_spec(read_case(write_case("stick", block_case(kF, motion, 2)).string()));
  ASSERT_EQ(run.result.status, "converged");
  const int m = int(run.result.contact->solution.friction_state.size());
  const int stuck = stuck_without_slip(run);
  EXPECT_GE(stuck, m - 2);  // the corners may slip
  const ObstacleReaction& r = run.result.reactions.at(0);
  EXPECT_GT(r.tangential_force[0], 0.0);
  EXPECT_LT(r.tangential_force[0], kF * r.normal_force);
}

// Path dependence: the sliding block's plane moved to +delta, back to 0,
// on to -delta and back to 0 (SmallStrainFriction stepped by hand through
// the obstacle's positions, the slip history carried from step to step).
// Far enough to slide each way: the force is +f N at +delta and -f N at
// -delta; back at 0 it is what the way there left, -f N after sliding
// back, where the start had none: the loop friction implies.
TEST(Friction, BlockDraggedThereAndBackIsAHysteresisLoop) {
  const FrictionRun run = run_spec(read_case(write_case("loop", block_case(kF, 0.01, 1)).string()));
  const Model& m = run.model;
  LinearSystem sys = assemble_linear_elasticity(m.body, *m.dofs, m.material, Eigen::VectorXd::Zero(2));
  add_pressure_load(m.body, *m.dofs, resolve_faces(m, {"top"}, "pressure"), 0.01, sys.f);
  const RigidModes modes = free_rigid_modes(m.body, *m.dofs);
  ContactSolverOptions opt;
  opt.complementarity_scale = m.spec.E / m.mesh_size;
  SparseCholesky chol;
  const WeightedGapOperator start = assemble_contact_operator(m, 0.0);
  SmallStrainFriction friction(sys.K, sys.f, start, modes, chol, opt);
  const std::vector<double> path = {0, 0.5, 1, 0.5, 0, -0.5, -1, -0.5, 0};
  std::vector<double> force;
  for (double t : path) {
    const WeightedGapOperator op = assemble_contact_operator(m, t);
    const ContactSolution s = friction.step(op);
    ASSERT_TRUE(s.converged) << s.status << " at t = " << t;
    force.push_back(-(s.lambda_t.array() * op.weights.array()).sum());
  }
  const double fN = kF * 0.01;
  EXPECT_NEAR(force[0], 0.0, kRoundOff * fN);
  EXPECT_NEAR(force[2], fN, kRoundOff * fN);
  EXPECT_NEAR(force[6], -fN, kRoundOff * fN);
  EXPECT_NEAR(force[4], -fN, kRoundOff * fN);  // back at 0 from +delta: sliding back
  EXPECT_NEAR(force[8], fN, kRoundOff * fN);   // back at 0 from -delta
  EXPECT_GT(force[1] - force[3], fN);          // at +delta/2 on the way there and back
  for (double F : force) EXPECT_LE(std::abs(F), fN * (1 + kRoundOff));
}

// Force-driven: the block free of Dirichlet conditions, pressed by P on
// its top and pushed along x by a pressure q on its left side, held along x
// by friction only.  Below f N it does not slide: the friction force is the
// push to round-off (the rigid motions' balance rows) and the stuck
// multipliers do not slip; above f N nothing holds it and the run says so.
std::string pushed_block_case(double push) {
  return "[geometry]\nshape = \"rectangle\"\nsize = [1.0, 0.25]\n"
         "[mesh]\ndegree = 2\nelements = [16, 4]\n"
         "[material]\nE = 1.0\nnu = 0.0\n"
         "[[pressure]]\nfaces = [\"top\"]\nvalue = 0.01\n"
         "[[pressure]]\nfaces = [\"left\"]\nvalue = " + std::to_string(push) + "\n"
         "[contact]\nface = \"bottom\"\nfriction = 0.3\n"
         "[contact.obstacle]\ntype = \"plane\"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]\n";
}

TEST(Friction, PushedBlockBelowFNDoesNotSlide) {
  const double Q = 0.5 * kF * 0.01, q = Q / 0.25;  // half of f N, over the side's height 0.25
  const FrictionRun run = run_spec(read_case(write_case("pushed", pushed_block_case(q)).string()));
  ASSERT_EQ(run.result.status, "converged");
  const int m = int(run.result.contact->solution.friction_state.size());
  const int stuck = stuck_without_slip(run);
  EXPECT_GE(stuck, m / 2);
  const ObstacleReaction& r = run.result.reactions.at(0);
  EXPECT_NEAR(r.normal_force, 0.01, kRoundOff * 0.01);
  EXPECT_NEAR(r.tangential_force[0], -Q, kRoundOff * Q);  // along -x: it holds the push
}

TEST(Friction, PushedBlockAboveFNIsNotHeld) {
  const double q = 1.5 * kF * 0.01 / 0.25;
  const FrictionRun run = run_spec(read_case(write_case("pushed_off", pushed_block_case(q)).string()));
  EXPECT_NE(run.result.status, "converged");
}

// A block [0, 1]^2 x [0, 0.25] pressed by 0.01 on a plane z = 0, its top
// held in x and y, the plane dragged by (motion, 0) in `steps` steps.
std::string box_case(const std::string& elements, double nu, const std::string& motion, int steps) {
  return "[geometry]\nshape = \"box\"\nsize = [1.0, 1.0, 0.25]\n[mesh]\ndegree = 2\nelements = " + elements +
         "\n[material]\nE = 1.0\nnu = " + std::to_string(nu) +
         "\n[[dirichlet]]\nfaces = [\"top\"]\ncomponent = \"x\"\n"
         "[[dirichlet]]\nfaces = [\"top\"]\ncomponent = \"y\"\n"
         "[[pressure]]\nfaces = [\"top\"]\nvalue = 0.01\n"
         "[contact]\nface = \"bottom\"\nfriction = 0.3\n"
         "[contact.obstacle]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\nmotion = [" +
         motion + ", 0.0]\n[loading]\nsteps = " + std::to_string(steps) + "\n";
}

// 3D: the cone is a disc.  The plane dragged along (3, 4, 0) under a block
// pressed on it: every multiplier slides, on the disc, and the tangential
// force is f N along (0.6, 0.8) (a square cone would give f N on each axis,
// along (0.71, 0.71)).
TEST(Friction, SlidingBlock3DForceIsOnTheDisc) {
  const std::string text = box_case("[6, 6, 2]", 0.0, "0.03, 0.04", 2);
  const FrictionRun run = run_spec(read_case(write_case("slide3d", text).string()));
  ASSERT_EQ(run.result.status, "converged");
  const ObstacleReaction& r = run.result.reactions.at(0);
  EXPECT_NEAR(r.normal_force, 0.01, kRoundOff * 0.01);
  // Each multiplier slides along its own slip, the plane's motion less the
  // block's elastic shear, which varies over the face (the corners): the
  // force's direction is the motion's to kDirection, and its size f N to
  // kSize relative, from below (measured: 3.4e-5 and 9.4e-8).
  constexpr double kDirection = 1e-4, kSize = 1e-6;
  igac_test::expect_sliding_on_the_disc(run.result.contact->solution, r, kF, kRoundOff, kDirection, kSize);
}

// 3D partial slip: the block dragged a tenth of the way to sliding (nu =
// 0.3): the corners slip, the rest sticks; the semismooth Newton step across
// the slip direction settles each step in a few iterations (measured: 5, 5,
// 4, 4, 4; the direction's fixed point alone did not settle in 100).
TEST(Friction, Block3DPartialSlipSettles) {
  const std::string text = box_case("[12, 12, 3]", 0.3, "0.0003, 0.0004", 4);
  const FrictionRun run = run_spec(read_case(write_case("partial3d", text).string()));
  ASSERT_EQ(run.result.status, "converged");
  const ContactSolution& s = run.result.contact->solution;
  constexpr int kMaxIterationsPerStep = 10;
  for (int n : s.step_iterations) EXPECT_LE(n, kMaxIterationsPerStep);
  int stuck = 0, sliding = 0;
  for (size_t K = 0; K < s.friction_state.size(); ++K) {
    stuck += s.friction_state[K] == kStick;
    sliding += s.friction_state[K] == kSlip;
    if (s.friction_state[K] == kSlip)
      EXPECT_NEAR(s.lambda_t.segment(2 * K, 2).norm(), -kF * s.lambda[K], kRoundOff * -s.lambda.minCoeff());
    if (s.friction_state[K] == kStick)
      EXPECT_LE(s.lambda_t.segment(2 * K, 2).norm(), -kF * s.lambda[K] * (1 + kRoundOff));
  }
  EXPECT_GT(stuck, 0);
  EXPECT_GT(sliding, 0);
  const ObstacleReaction& r = run.result.reactions.at(0);
  EXPECT_LT(r.tangential_force.norm(), kF * r.normal_force);
}

// A block touching a plane at rest (no load: the plane's motion is the
// only one), as the first step of a moving obstacle poses it: the solution
// is zero and the multipliers stay stuck, as they start.  Solved by an
// iteration, the states were decided on tractions of 1e-15 (on a 32 x 32
// face, 76 of 1024 multipliers came out sliding), and the next step started
// from there; the plane's first move then settles from the stuck start.
TEST(Friction, BlockAtRestOnAPlaneStaysStuck) {
  const std::string text =
      "[geometry]\nshape = \"box\"\nsize = [1.0, 1.0, 0.25]\n[mesh]\ndegree = 2\nelements = [6, 6, 2]\n"
      "[material]\nE = 1.0\nnu = 0.3\n"
      "[[dirichlet]]\nfaces = [\"top\"]\ncomponent = \"x\"\n[[dirichlet]]\nfaces = [\"top\"]\ncomponent = \"y\"\n"
      "[[dirichlet]]\nfaces = [\"top\"]\ncomponent = \"z\"\n"
      "[contact]\nface = \"bottom\"\nfriction = 0.3\n[contact.obstacle]\ntype = \"plane\"\n"
      "point = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\nmotion = [0.0003, 0.0004, 0.001]\n";
  const Model m = build_model(read_case(write_case("rest3d", text).string()));
  const LinearSystem sys = assemble_linear_elasticity(m.body, *m.dofs, m.material, Eigen::VectorXd::Zero(3));
  const RigidModes modes = free_rigid_modes(m.body, *m.dofs);
  ContactSolverOptions opt;
  opt.complementarity_scale = m.spec.E / m.mesh_size;
  opt.mesh_size = m.mesh_size;
  SparseCholesky chol;
  const WeightedGapOperator start = assemble_contact_operator(m, 0.0);
  SmallStrainFriction friction(sys.K, sys.f, start, modes, chol, opt);
  const ContactSolution rest = friction.step(start);
  ASSERT_TRUE(rest.converged) << rest.status;
  EXPECT_EQ(rest.u.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(rest.lambda.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_TRUE(rest.active_set_sizes.empty());  // no iteration
  for (size_t K = 0; K < rest.friction_state.size(); ++K) EXPECT_EQ(rest.friction_state[K], kStick) << "multiplier " << K;
  const ContactSolution moved = friction.step(assemble_contact_operator(m, 1.0));
  ASSERT_TRUE(moved.converged) << moved.status;
  EXPECT_GT(moved.lambda.cwiseAbs().maxCoeff(), 0.0);
}

// The stick zone's half width (tests/support/stick_zone.hpp) against
// c = a sqrt(1 - Q / (f N)).
TEST(Friction, CattaneoMindlinStickZone) {
  const FrictionRun run = run_spec(read_case(kSourceDir + "/cases/cattaneo_mindlin.toml"));
  ASSERT_EQ(run.result.status, "converged");
  const ContactSolution& s = run.result.contact->solution;
  for (size_t K = 0; K < s.friction_state.size(); ++K)
    if (s.friction_state[K] == kSlip)  // on the cone
      EXPECT_NEAR(std::abs(s.lambda_t[K]), -kF * s.lambda[K], kRoundOff * -s.lambda.minCoeff());
  const igac_test::StickZone z = igac_test::stick_zone(*run.model.contacts[0].face, s.friction_state);
  ASSERT_GE(z.stuck, 3);
  const ObstacleReaction& r = run.result.reactions.at(0);
  const double N = r.normal_force, Q = r.tangential_force[0];
  const double E = run.model.spec.E, nu = run.model.spec.nu, R = 1.0;
  const double a = std::sqrt(4 * N * R * (1 - nu * nu) / (std::numbers::pi * E));
  ASSERT_GT(Q, 0.0);
  ASSERT_LT(Q, kF * N);
  const double c = a * std::sqrt(1 - Q / (kF * N));
  std::printf("Cattaneo-Mindlin: N = %.6g, Q = %.6g (Q/fN = %.4f), a = %.5f, c = %.5f, c_h = %.5f, spacing = %.5f, "
              "zone half width %.5f\n",
              N, Q, Q / (kF * N), a, c, z.half_width, z.spacing, z.zone_half_width);
  EXPECT_NEAR(z.half_width, c, z.spacing);
}

// A frictional and a frictionless contact together: the block free of
// Dirichlet conditions, pressed by P on its top onto the frictional plane,
// pushed by q on its right side against a frictionless wall at x = 0.  It
// stopped at the first iteration, "singular contact system ... (with
// friction: a load along the obstacle above f times the normal force slides
// the body away)": the wall's multipliers started stuck, with tangential
// rows of zeros.  Now it converges and balances: the plane carries P, the
// wall and the plane's friction together carry the push, the wall no
// tangential force.
TEST(Friction, FrictionalAndFrictionlessContactsTogether) {
  const double P = 0.01, q = 0.2 * kF * P / 0.25;  // a push of 0.2 f N over the side's height 0.25
  const std::string text = "[geometry]\nshape = \"rectangle\"\nsize = [1.0, 0.25]\n"
                           "[mesh]\ndegree = 2\nelements = [16, 4]\n[material]\nE = 1.0\nnu = 0.0\n"
                           "[[pressure]]\nfaces = [\"top\"]\nvalue = " + std::to_string(P) + "\n"
                           "[[pressure]]\nfaces = [\"right\"]\nvalue = " + std::to_string(q) + "\n"
                           "[[contact]]\nface = \"bottom\"\nfriction = 0.3\n"
                           "[contact.obstacle]\ntype = \"plane\"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]\n"
                           "[[contact]]\nface = \"left\"\n"
                           "[contact.obstacle]\ntype = \"plane\"\npoint = [0.0, 0.0]\nnormal = [1.0, 0.0]\n";
  const FrictionRun run = run_spec(read_case(write_case("wall", text).string()));
  ASSERT_EQ(run.result.status, "converged");
  ASSERT_EQ(run.result.reactions.size(), 2u);
  const ObstacleReaction &plane = run.result.reactions[0], &wall = run.result.reactions[1];
  EXPECT_NEAR(plane.normal_force, P, kRoundOff * P);
  EXPECT_GT(wall.normal_force, 0.0);
  // x: the wall's normal force (+x on the body) and the plane's friction
  // (tangent +x) hold the push q h.
  EXPECT_NEAR(wall.normal_force + plane.tangential_force[0], q * 0.25, kRoundOff * q);
  ASSERT_EQ(wall.tangential_force.size(), 1);
  EXPECT_EQ(wall.tangential_force[0], 0.0);
}

// [loading] on a frictionless linear case was refused, so a sweep of
// friction 0, 0.1, ... over one case file broke at 0.  It is read, and the
// case is still the one linear solve.
TEST(Friction, SweepFromZeroKeepsTheLoadingTable) {
  const std::string loading = "[loading]\nsteps = 4\n";
  const FrictionRun with = run_spec(read_case(write_case("zero_loading", block_case(0.0, 0.0, 4) + loading).string()));
  const FrictionRun without = run_spec(read_case(write_case("zero", block_case(0.0, 0.0, 4)).string()));
  ASSERT_EQ(with.result.status, "converged");
  EXPECT_EQ(with.result.u, without.result.u);
  EXPECT_EQ(with.result.contact->solution.lambda, without.result.contact->solution.lambda);
  EXPECT_EQ(with.result.contact->solution.lambda_t.size(), 0);
}

TEST(Friction, BadCoefficientIsOneLine) {
  const std::string base = block_case(kF, 0.05, 2);
  for (const std::string& bad : {std::string("-0.1"), std::string("nan"), std::string("10.5")}) {
    std::string text = base;
    text.replace(text.find("friction = ") + 11, std::to_string(kF).size(), bad);
    try {
      read_case(write_case("bad", text).string());
      ADD_FAILURE() << "friction = " << bad << " accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("friction"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace igac
