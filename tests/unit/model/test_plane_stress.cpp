// SPDX-License-Identifier: BSD-3-Clause
// [model] kind = "plane_stress" through a whole run (materials/plane_stress.hpp
// is the law; this checks the model, the solve and the output fields):
//  - small deformation, a block pulled by a traction t on its right face,
//    held by symmetry: the plane stress state sigma_xx = t is in the
//    spline space, so u = (t X / E, -nu t Y / E) to the solve's round-off;
//    the ParaView fields give sigma_zz = 0 and eps_zz = -nu t / E (the
//    plate thins), and the supports carry t times the height;
//  - large deformation, a Neo-Hookean block under a dead traction T: the
//    homogeneous uniaxial stress state F = diag(l1, l2, l2), P_11 = T,
//    P_22 = P_33 = 0 (closed form by Newton on the two stretches), every
//    control point to the solve's tolerance, E_zz = (l2^2 - 1) / 2 in the fields;
//  - the Lame disc (cases/lame_cylinder.toml as plane stress) converges to
//    the plane stress closed form at the spline rate p + 1 in L2;
//  - 2D Hertz (cases/hertz2d.toml as plane stress) takes the plane stress
//    contact modulus E, and its pressure is within the plane strain run's
//    accuracy of it;
//  - what plane stress does not run is refused with one line naming why.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "contact/pressure.hpp"
#include "io/case_file.hpp"
#include "model/field_recovery.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/two_d_models.hpp"

namespace igac {
namespace {

constexpr double kE = 2.0, kNu = 0.3;

std::string block_case(const std::string& model, const std::string& load, const std::string& extra = "") {
  return "name = \"plane_stress_block\"\n[geometry]\nshape = \"rectangle\"\nsize = [2.0, 1.0]\n[mesh]\ndegree = 2\n"
         "elements = [3, 2]\n[material]\nmodel = \"" + model + "\"\nE = 2.0\nnu = 0.3\n"
         "[[dirichlet]]\nfaces = [\"left\"]\ncomponent = \"x\"\n[[dirichlet]]\nfaces = [\"bottom\"]\ncomponent = \"y\"\n"
         "[[traction]]\nfaces = [\"right\"]\nvalue = [" + load + ", 0.0]\n[loading]\nsteps = 4\n[output]\nvtk = false\n"
         "[model]\nkind = \"plane_stress\"\n" + extra;
}

double left_reaction(const RunResult& r) {
  for (const FaceReaction& f : r.dirichlet_reactions)
    if (f.face == "left") return f.force[0];
  ADD_FAILURE() << "no reaction of the left face";
  return NAN;
}

TEST(PlaneStress, SmallStrainBlockIsTheUniaxialStressState) {
  constexpr double t = 0.01;
  const Model m = build_model(read_case_text(block_case("linear_elastic", "0.01"), "plane_stress_block.toml"));
  const RunResult r = solve_model(m, quiet_run());
  const double error = igac_test::homogeneous_field_error(m.body, r.u, Eigen::Vector2d(t / kE, -kNu * t / kE).asDiagonal().toDenseMatrix());
  EXPECT_LT(error, 1e-14) << "plane strain would give u_y = -nu (1 + nu) t Y / E";
  EXPECT_NEAR(left_reaction(r), -t, 1e-15);
  const RecoveredFields f = recover_body_fields(body_bezier_mesh(m.body, r.u), m);
  const Eigen::Index n = f.stress.stress.rows();
  EXPECT_LT((f.stress.stress.col(0).array() - t).abs().maxCoeff(), 1e-13);
  EXPECT_LT(f.stress.stress.col(2).cwiseAbs().maxCoeff(), 1e-15) << "sigma_zz";
  EXPECT_LT((f.stress.strain.col(2).array() + kNu * t / kE).abs().maxCoeff(), 1e-15) << "eps_zz";
  EXPECT_GT(n, 0);
}

TEST(PlaneStress, NeoHookeanBlockMatchesTheUniaxialStressClosedForm) {
  constexpr double T = 0.6;  // a stretch of 1.3 along x
  const Model m = build_model(read_case_text(block_case("neo_hookean", "0.6"), "plane_stress_block.toml"));
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_TRUE(r.status.is_converged()) << r.status.text();
  const Eigen::Vector2d l = igac_test::neo_hookean_uniaxial_stretches(kE, kNu, T);
  const double error = igac_test::homogeneous_field_error(m.body, r.u, Eigen::Vector2d(l[0] - 1, l[1] - 1).asDiagonal().toDenseMatrix());
  std::printf("  plane stress uniaxial T = %.1f: l1 %.12f, l2 = l3 %.12f, max control-point error %.2e\n", T, l[0],
              l[1], error);
  EXPECT_GT(l[0], 1.25);
  EXPECT_LT(error, 1e-9);  // Newton stops at |R|/F <= 1e-10 (docs/design.md)
  EXPECT_NEAR(left_reaction(r), -T, 1e-9);
  const RecoveredFields f = recover_body_fields(body_bezier_mesh(m.body, r.u), m);
  EXPECT_LT((f.stress.strain.col(2).array() - (l[1] * l[1] - 1) / 2).abs().maxCoeff(), 1e-9) << "E_zz";
  EXPECT_LT(f.stress.stress.col(2).cwiseAbs().maxCoeff(), 1e-9) << "sigma_zz";
  EXPECT_LT((f.volume.jacobian.array() - l[0] * l[1] * l[1]).abs().maxCoeff(), 1e-9) << "J counts the thinning";
}

TEST(PlaneStress, LameDiscConvergesAtTheSplineRate) {
  igac_test::expect_lame_converges_at_the_spline_rate("plane_stress", 1e-5);
}

TEST(PlaneStress, HertzTakesThePlaneStressModulus) {
  const std::string text = igac_test::shipped_case("hertz2d.toml") + "\n[model]\nkind = \"plane_stress\"\n";
  const Model m = build_model(read_case_text(text, std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d_ps.toml"));
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_TRUE(r.hertz && r.pressure_error);
  double P = 0;
  for (const auto& p : m.spec.pressure) P += p.value;
  // Hertz's contact modulus E / (1 - nu^2) is E in plane stress: the plane
  // strain formula with nu = 0.
  const HertzSolution expected = hertz_cylinder(m.spec.radius, P, m.spec.E, 0.0);
  EXPECT_NEAR(r.hertz->p0, expected.p0, 1e-12 * r.hertz->p0);
  EXPECT_NEAR(r.hertz->a, expected.a, 1e-12 * r.hertz->a);
  const double rel = r.pressure_error->first / r.pressure_error->second;
  std::printf("  plane stress hertz2d: p0 %.6g, L2 pressure error %.3f %%\n", r.hertz->p0, 100 * rel);
  EXPECT_LT(rel, 0.03) << "cases/hertz2d.toml in plane strain: 2.4 %";
}

TEST(PlaneStress, WhatItDoesNotRunIsRefusedInOneLine) {
  std::string misspelt = block_case("linear_elastic", "0.01");
  misspelt.replace(misspelt.find("plane_stress\"\n"), 12, "plain_stress");
  igac_test::expect_kind_refused(misspelt, "plane_stress_block.toml", "unknown kind 'plain_stress'");
  std::string mixed = block_case("neo_hookean", "0.1");
  mixed.replace(mixed.find("nu = 0.3\n"), 9, "nu = 0.3\nformulation = \"mixed\"\n");
  igac_test::expect_kind_refused(mixed, "plane_stress_block.toml", "no mixed formulation");
  std::string follower = block_case("neo_hookean", "0.1");
  follower += "[[pressure]]\nfaces = [\"top\"]\nvalue = 0.01\n";
  igac_test::expect_kind_refused(follower, "plane_stress_block.toml", "pressure = \"dead\"");
  const std::string three_d = igac_test::shipped_case("hertz3d.toml") + "\n[model]\nkind = \"plane_stress\"\n";
  igac_test::expect_kind_refused(three_d, "plane_stress_block.toml", "a 2D model");
  // a dead pressure runs
  std::string dead = follower;
  dead.replace(dead.find("steps = 4\n"), 10, "steps = 4\npressure = \"dead\"\n");
  EXPECT_NO_THROW(read_case_text(dead, "plane_stress_block.toml"));
}

}  // namespace
}  // namespace igac
