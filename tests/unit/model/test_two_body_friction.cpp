// SPDX-License-Identifier: BSD-3-Clause
// Coulomb friction between two deformable bodies, small deformation
// (contact/mortar_gap.hpp: the tangential rows in the mortar loop;
// contact/small_strain_friction.hpp: the active set):
//  - the sliding-block patch test on an elastic base: a block pressed on a
//    second block of the same width (nu = 0: the press alone strains
//    nothing along the face), their meshes not matching, the lower block
//    then moved along x with its support (master_motion): while everything
//    slides the tangential force is f N to round-off; a motion far below
//    the blocks' elastic shear leaves the multipliers stuck, slip zero;
//  - the forces of the contact on the two bodies, normal and tangential,
//    are opposite to round-off;
//  - Cattaneo-Mindlin between two bodies of one material
//    (cases/cattaneo_mindlin_two_bodies.toml): the stick half width is
//    c = a sqrt(1 - Q / (f N)) within one multiplier spacing, a Hertz's
//    half width for the pair's modulus; swapping slave and master gives
//    the same stick zone within a multiplier spacing;
//  - 3D: a box dragged on an elastic box slides on the disc, f N along the
//    motion, the forces on the two boxes opposite to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/igac_process.hpp"
#include "tests/support/stick_zone.hpp"

namespace igac {
namespace {
namespace fs = std::filesystem;

const fs::path kCases = fs::path(IGAC_SOURCE_DIR) / "cases";
constexpr double kF = 0.3;
constexpr double kRoundOff = 1e-11;

struct PairRun {
  Model model;
  RunResult result;
};

PairRun run_text(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "igac_two_body_friction";
  fs::create_directories(dir);
  std::ofstream(dir / (name + ".toml")) << text;
  PairRun run{build_model(read_case((dir / (name + ".toml")).string())), {}};
  run.result = solve_model(run.model, quiet_run());
  return run;
}

// An upper block [0, 1] x [0.25, 0.5] (16 elements along x) pressed by 0.01
// on a lower block [0, 1] x [0, 0.25] (12 elements), its top held in x; the
// lower block stands on y = 0, held there in x and y, and is moved with that
// support by (motion, 0) in `steps` steps.
std::string blocks_case(double motion, int steps) {
  auto body = [](const char* name, double y0, int nx) {
    return std::string("[[body]]\nname = \"") + name + "\"\n[body.geometry]\nshape = \"rectangle\"\n"
           "size = [1.0, 0.25]\ntranslate = [0.0, " + std::to_string(y0) + "]\n[body.mesh]\ndegree = 2\n"
           "elements = [" + std::to_string(nx) + ", 4]\n[body.material]\nE = 1.0\nnu = 0.0\n";
  };
  return body("upper", 0.25, 16) + body("lower", 0.0, 12) +
         "[[dirichlet]]\nfaces = [\"upper:top\"]\ncomponent = \"x\"\n"
         "[[dirichlet]]\nfaces = [\"lower:bottom\"]\ncomponent = \"x\"\n"
         "[[dirichlet]]\nfaces = [\"lower:bottom\"]\ncomponent = \"y\"\n"
         "[[pressure]]\nfaces = [\"upper:top\"]\nvalue = 0.01\n"
         "[[contact]]\nface = \"upper:bottom\"\nmaster = \"lower:top\"\nfriction = 0.3\nmaster_motion = [" +
         std::to_string(motion) + ", 0.0]\n[loading]\nsteps = " + std::to_string(steps) + "\n";
}

// The contact's force on each body, -(G^T lambda + T^T lambda_t) summed over
// the free dofs of its patches (patch 0 the slave's body, 1 the master's in
// the cases here), per component.
std::array<Eigen::VectorXd, 2> contact_forces(const PairRun& run) {
  const ContactSolve& c = *run.result.contact;
  const Eigen::VectorXd force = -(c.op.G.transpose() * c.solution.lambda + c.op.T.transpose() * c.solution.lambda_t);
  const Model& m = run.model;
  const int dim = m.body.space_dim();
  const std::vector<int> part = m.body.parts();
  std::array<Eigen::VectorXd, 2> out{Eigen::VectorXd::Zero(dim), Eigen::VectorXd::Zero(dim)};
  std::vector<char> seen(m.body.num_control_points(), 0);  // (joined patches share their interface's points)
  for (int k = 0; k < m.body.num_patches(); ++k)
    for (int a : m.body.body_cps(k)) {
      if (seen[a]++) continue;
      for (int i = 0; i < dim; ++i)
        if (const int eq = m.dofs->equation(a * dim + i); eq >= 0) out[part[k] == part[0] ? 0 : 1][i] += force[eq];
    }
  return out;
}

TEST(TwoBodyFriction, SlidingBlockOnAnElasticBlockForceIsFTimesN) {
  const PairRun run = run_text("slide", blocks_case(0.05, 4));
  ASSERT_EQ(run.result.status, "converged");
  const ContactSolution& s = run.result.contact->solution;
  for (size_t K = 0; K < s.friction_state.size(); ++K) EXPECT_EQ(s.friction_state[K], kSlip) << "multiplier " << K;
  const ObstacleReaction& r = run.result.reactions.at(0);
  ASSERT_EQ(r.tangential_force.size(), 1);
  EXPECT_NEAR(r.normal_force, 0.01, kRoundOff * 0.01);
  // The lower block moved along +x drags the upper one along +x.
  EXPECT_NEAR(r.tangential_force[0], kF * r.normal_force, kRoundOff * r.normal_force);
  // Its support carries the rest: the lower block's bottom -f N along x.
  const auto f = contact_forces(run);
  EXPECT_NEAR(f[0][0], kF * 0.01, kRoundOff * 0.01);
  EXPECT_NEAR(f[0][1], 0.01, kRoundOff * 0.01);
  EXPECT_NEAR((f[0] + f[1]).norm(), 0.0, kRoundOff * 0.01);
  // The output displacement of the lower block carries its motion.
  const int corner = run.model.body.body_cps(1).front();
  EXPECT_NEAR(run.result.u(corner, 0), 0.05, 1e-15);
}

TEST(TwoBodyFriction, BlockBelowSlidingOnAnElasticBlockSticks) {
  const PairRun run = run_text("stick", blocks_case(1e-6, 2));
  ASSERT_EQ(run.result.status, "converged");
  const ContactSolution& s = run.result.contact->solution;
  const int stuck = igac_test::stuck_without_slip(s, kRoundOff * run.result.u.cwiseAbs().maxCoeff());
  EXPECT_GE(stuck, int(s.friction_state.size()) - 2);  // the corners may slip
  const ObstacleReaction& r = run.result.reactions.at(0);
  EXPECT_GT(r.tangential_force[0], 0.0);
  EXPECT_LT(r.tangential_force[0], kF * r.normal_force);
}

// 3D: a box [0, 1]^2 x [0.25, 0.5] (4 x 4 elements across) pressed by 0.01
// on a box [0, 1]^2 x [0, 0.25] (3 x 3), its top held in x and y; the lower
// box moved along (3, 4, 0) with its support: every multiplier slides on the
// disc |lambda_t| = -f lambda_n, and the forces on the two boxes are opposite.
TEST(TwoBodyFriction, SlidingBoxOnAnElasticBoxForceIsOnTheDisc) {
  auto body = [](const char* name, double z0, int n) {
    return std::string("[[body]]\nname = \"") + name + "\"\n[body.geometry]\nshape = \"box\"\n"
           "size = [1.0, 1.0, 0.25]\ntranslate = [0.0, 0.0, " + std::to_string(z0) + "]\n[body.mesh]\ndegree = 2\n"
           "elements = [" + std::to_string(n) + ", " + std::to_string(n) + ", 2]\n[body.material]\nE = 1.0\nnu = 0.0\n";
  };
  const std::string text = body("upper", 0.25, 4) + body("lower", 0.0, 3) +
                           "[[dirichlet]]\nfaces = [\"upper:top\"]\ncomponent = \"x\"\n"
                           "[[dirichlet]]\nfaces = [\"upper:top\"]\ncomponent = \"y\"\n"
                           "[[dirichlet]]\nfaces = [\"lower:bottom\"]\ncomponent = \"x\"\n"
                           "[[dirichlet]]\nfaces = [\"lower:bottom\"]\ncomponent = \"y\"\n"
                           "[[dirichlet]]\nfaces = [\"lower:bottom\"]\ncomponent = \"z\"\n"
                           "[[pressure]]\nfaces = [\"upper:top\"]\nvalue = 0.01\n"
                           "[[contact]]\nface = \"upper:bottom\"\nmaster = \"lower:top\"\nfriction = 0.3\n"
                           "master_motion = [0.03, 0.04, 0.0]\n[loading]\nsteps = 2\n";
  const PairRun run = run_text("slide3d", text);
  ASSERT_EQ(run.result.status, "converged");
  const ObstacleReaction& r = run.result.reactions.at(0);
  EXPECT_NEAR(r.normal_force, 0.01, kRoundOff * 0.01);
  // As on a rigid plane (tests/unit/model/test_friction.cpp), with wider
  // bounds (measured: direction 1.2e-4, size 2.2e-6).
  constexpr double kDirection = 1e-3, kSize = 1e-5;
  igac_test::expect_sliding_on_the_disc(run.result.contact->solution, r, kF, kRoundOff, kDirection, kSize);
  const auto f = contact_forces(run);
  std::printf("3D sliding box on a box: tangential force %.10g (f N = %.10g), direction (%.6f, %.6f); slave + master "
              "forces %.3g\n", r.tangential_force.norm(), kF * r.normal_force, r.tangential_force[0] / r.tangential_force.norm(),
              r.tangential_force[1] / r.tangential_force.norm(), (f[0] + f[1]).norm());
  EXPECT_NEAR((f[0] + f[1]).norm(), 0.0, kRoundOff * f[0].norm());
  EXPECT_NEAR(f[0][2], 0.01, kRoundOff * 0.01);
}

// cases/cattaneo_mindlin_two_bodies.toml with slave and master swapped
// (the block's top the slave, the roller's arc the master, the roller moved
// the other way: the same relative motion).
CaseSpec swapped(CaseSpec spec) {
  ContactSpec& c = spec.contacts.at(0);
  std::swap(c.face, c.master);
  for (double& x : c.master_motion) x = -x;
  return spec;
}

struct Zone {
  igac_test::StickZone zone;
  double N = 0, Q = 0;
};

Zone cattaneo_mindlin(const CaseSpec& spec) {
  PairRun run{build_model(spec), {}};
  run.result = solve_model(run.model, quiet_run());
  EXPECT_EQ(run.result.status, "converged");
  const ContactSolution& s = run.result.contact->solution;
  for (size_t K = 0; K < s.friction_state.size(); ++K)
    if (s.friction_state[K] == kSlip)  // on the cone
      EXPECT_NEAR(std::abs(s.lambda_t[K]), -kF * s.lambda[K], kRoundOff * -s.lambda.minCoeff());
  // Normal and tangential: the force on the slave is minus the force on the master.
  const auto f = contact_forces(run);
  EXPECT_GT(std::abs(f[0][0]), 0.1 * std::abs(f[0][1]));
  EXPECT_NEAR((f[0] + f[1]).norm(), 0.0, kRoundOff * f[0].norm());
  const ObstacleReaction& r = run.result.reactions.at(0);
  return {igac_test::stick_zone(*run.model.contacts[0].face, s.friction_state), r.normal_force,
          std::abs(r.tangential_force[0])};
}

TEST(TwoBodyFriction, CattaneoMindlinStickZoneAndSwappedSlaveMaster) {
  const CaseSpec spec = read_case((kCases / "cattaneo_mindlin_two_bodies.toml").string());
  const Zone z = cattaneo_mindlin(spec), w = cattaneo_mindlin(swapped(spec));
  const double E = spec.bodies.at(0).E, nu = spec.bodies.at(0).nu, R = 1.0;
  const double E_pair = E / 2;  // two bodies of one material: 1/E* = 2 (1 - nu^2) / E
  const double a = std::sqrt(4 * z.N * R * (1 - nu * nu) / (std::numbers::pi * E_pair));
  ASSERT_GT(z.Q, 0.2 * kF * z.N);
  ASSERT_LT(z.Q, kF * z.N);
  const double c = a * std::sqrt(1 - z.Q / (kF * z.N));
  std::printf("Cattaneo-Mindlin, two bodies: N = %.6g, Q = %.6g (Q/fN = %.4f), a = %.5f, c = %.5f, c_h = %.5f, "
              "spacing = %.5f; swapped: N = %.6g, Q = %.6g, c_h = %.5f, spacing = %.5f\n",
              z.N, z.Q, z.Q / (kF * z.N), a, c, z.zone.half_width, z.zone.spacing, w.N, w.Q, w.zone.half_width,
              w.zone.spacing);
  ASSERT_GE(z.zone.stuck, 3);
  EXPECT_NEAR(z.zone.half_width, c, z.zone.spacing);
  EXPECT_NEAR(w.zone.half_width, z.zone.half_width, std::max(z.zone.spacing, w.zone.spacing));
}

}  // namespace
}  // namespace igac
