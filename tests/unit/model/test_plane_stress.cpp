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
#include <fstream>
#include <sstream>
#include <string>

#include "contact/pressure.hpp"
#include "io/case_file.hpp"
#include "model/field_recovery.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

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

std::string shipped(const std::string& name) {
  std::ifstream in(std::string(IGAC_SOURCE_DIR) + "/cases/" + name);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
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
  double error = 0;
  for (int a = 0; a < m.body.num_control_points(); ++a) {
    const Eigen::RowVector2d X = m.body.points().row(a);
    error = std::max(error, (r.u.row(a) - Eigen::RowVector2d(t * X[0] / kE, -kNu * t * X[1] / kE)).norm());
  }
  EXPECT_LT(error, 1e-14) << "plane strain would give u_y = -nu (1 + nu) t Y / E";
  EXPECT_NEAR(left_reaction(r), -t, 1e-15);
  const RecoveredFields f = recover_body_fields(body_bezier_mesh(m.body, r.u), m);
  const Eigen::Index n = f.stress.stress.rows();
  EXPECT_LT((f.stress.stress.col(0).array() - t).abs().maxCoeff(), 1e-13);
  EXPECT_LT(f.stress.stress.col(2).cwiseAbs().maxCoeff(), 1e-15) << "sigma_zz";
  EXPECT_LT((f.stress.strain.col(2).array() + kNu * t / kE).abs().maxCoeff(), 1e-15) << "eps_zz";
  EXPECT_GT(n, 0);
}

// (l1, l2) of the Neo-Hookean uniaxial stress P_11 = T, P_22 = P_33 = 0
// with l3 = l2: mu (l1 - 1/l1) + lambda ln J / l1 = T, mu (l2 - 1/l2) +
// lambda ln J / l2 = 0, J = l1 l2^2.
Eigen::Vector2d uniaxial_stress_stretches(double T) {
  const double mu = kE / (2 * (1 + kNu)), lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu));
  Eigen::Vector2d l(1, 1);
  for (int it = 0; it < 50; ++it) {
    const double a = l[0], b = l[1], lnJ = std::log(a * b * b);
    const Eigen::Vector2d r(mu * (a - 1 / a) + lambda * lnJ / a - T, mu * (b - 1 / b) + lambda * lnJ / b);
    Eigen::Matrix2d J;
    J << mu * (1 + 1 / (a * a)) + lambda * (1 - lnJ) / (a * a), 2 * lambda / (a * b),  //
        lambda / (a * b), mu * (1 + 1 / (b * b)) + lambda * (2 - lnJ) / (b * b);
    l -= J.partialPivLu().solve(r);
  }
  return l;
}

TEST(PlaneStress, NeoHookeanBlockMatchesTheUniaxialStressClosedForm) {
  constexpr double T = 0.6;  // a stretch of 1.3 along x
  const Model m = build_model(read_case_text(block_case("neo_hookean", "0.6"), "plane_stress_block.toml"));
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_TRUE(r.status.is_converged()) << r.status.text();
  const Eigen::Vector2d l = uniaxial_stress_stretches(T);
  double error = 0;
  for (int a = 0; a < m.body.num_control_points(); ++a) {
    const Eigen::RowVector2d X = m.body.points().row(a);
    error = std::max(error, (r.u.row(a) - Eigen::RowVector2d((l[0] - 1) * X[0], (l[1] - 1) * X[1])).norm());
  }
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
  const std::string text = shipped("lame_cylinder.toml") + "\n[model]\nkind = \"plane_stress\"\n";
  double previous = 0;
  for (int refine : {1, 2, 3}) {
    CaseSpec spec = read_case_text(text, std::string(IGAC_SOURCE_DIR) + "/cases/lame_ps.toml");
    apply_overrides(spec, std::nullopt, refine);
    const RunResult r = solve_model(build_model(spec), quiet_run());
    ASSERT_TRUE(r.displacement_errors);
    const double e = r.displacement_errors->l2 / r.displacement_errors->ref_l2;
    std::printf("  plane stress Lame disc, refine %d: relative L2 error %.3e\n", refine, e);
    if (previous > 0) EXPECT_GT(std::log2(previous / e), 2.7) << "p = 2: L2 rate 3";
    previous = e;
  }
  EXPECT_LT(previous, 1e-5);
}

TEST(PlaneStress, HertzTakesThePlaneStressModulus) {
  const std::string text = shipped("hertz2d.toml") + "\n[model]\nkind = \"plane_stress\"\n";
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

void expect_refused(const std::string& text, const std::string& why) {
  try {
    read_case_text(text, "plane_stress_block.toml");
    ADD_FAILURE() << "accepted; expected: " << why;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(why), std::string::npos) << message;
    EXPECT_NE(message.find("[model] kind"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  }
}

TEST(PlaneStress, WhatItDoesNotRunIsRefusedInOneLine) {
  std::string misspelt = block_case("linear_elastic", "0.01");
  misspelt.replace(misspelt.find("plane_stress\"\n"), 12, "plain_stress");
  expect_refused(misspelt, "unknown kind 'plain_stress'");
  std::string mixed = block_case("neo_hookean", "0.1");
  mixed.replace(mixed.find("nu = 0.3\n"), 9, "nu = 0.3\nformulation = \"mixed\"\n");
  expect_refused(mixed, "no mixed formulation");
  std::string follower = block_case("neo_hookean", "0.1");
  follower += "[[pressure]]\nfaces = [\"top\"]\nvalue = 0.01\n";
  expect_refused(follower, "pressure = \"dead\"");
  const std::string three_d = shipped("hertz3d.toml") + "\n[model]\nkind = \"plane_stress\"\n";
  expect_refused(three_d, "a 2D model");
  // a dead pressure runs
  std::string dead = follower;
  dead.replace(dead.find("steps = 4\n"), 10, "steps = 4\npressure = \"dead\"\n");
  EXPECT_NO_THROW(read_case_text(dead, "plane_stress_block.toml"));
}

}  // namespace
}  // namespace igac
