// SPDX-License-Identifier: BSD-3-Clause
// Interference fits ([contact] interference = true): a disc shrunk onto a
// shaft (cases/press_fit.toml: a solid shaft of radius b (1 + i) in a ring
// b = 1 .. c = 2, one material, quarters held by symmetry).  Closed form
// (plane stress; plane strain with E / (1 - nu^2)): the contact pressure
//   p = E delta (c^2 - b^2) / (2 b c^2),  delta = i b,
// which the ring carries in its hoop force: the cut x = 0 of the quarter
// ring holds p b (the ring's equilibrium, whatever its stress profile).
//  - small deformation at i = 0.15 % and 1 %: that reaction within 0.5 % of
//    p b, in plane stress and plane strain; the peak multiplier is the
//    pressure on the shaft's face, p b / (b (1 + i)) to first order;
//  - large deformation (Neo-Hookean) at 0.15 %: the same closed form to
//    0.5 %; at 7 % (an overlap of 5 % of the face's size) it converges;
//  - friction (0.1) changes nothing in this radial fit;
//  - against a rigid plane in 3D the fit ends where a moving plane ends;
//  - an overlap not declared stays an error naming the key, and a tied
//    contact refuses interference.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

std::string press_fit(double i, const std::string& kind = "plane_stress", const std::string& law = "linear_elastic",
                      const std::string& contact_extra = "") {
  std::ifstream in(std::string(IGAC_SOURCE_DIR) + "/cases/press_fit.toml");
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  const auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    if (at == std::string::npos) throw std::logic_error("press_fit.toml has no " + from);
    text.replace(at, from.size(), to);
  };
  replace("radius = 1.0015", "radius = " + std::to_string(1 + i));
  replace("kind = \"plane_stress\"", "kind = \"" + kind + "\"");
  for (int body = 0; body < 2; ++body) replace("model = \"linear_elastic\"", "model = \"" + law + "\"");
  replace("interference = true", "interference = true\n" + contact_extra);
  return text;
}

RunResult run(const std::string& text) {
  return solve_model(build_model(read_case_text(text, std::string(IGAC_SOURCE_DIR) + "/cases/press_fit.toml")),
                     quiet_run());
}

double ring_cut_force(const RunResult& r) {
  for (const FaceReaction& f : r.dirichlet_reactions)
    if (f.face == "ring:left") return -f.force[0];
  ADD_FAILURE() << "no reaction of ring:left";
  return NAN;
}

// p b of the closed form (E = 1, nu = 0.3, b = 1, c = 2).
double closed_form_cut_force(double i, const std::string& kind) {
  const double E = kind == "plane_stress" ? 1.0 : 1.0 / (1 - 0.3 * 0.3), b = 1, c = 2;
  return E * i * b * (c * c - b * b) / (2 * b * c * c) * b;
}

TEST(Interference, SmallDeformationPressFitsMatchTheClosedForm) {
  for (const std::string kind : {"plane_stress", "plane_strain"})
    for (const double i : {0.0015, 0.01}) {
      const RunResult r = run(press_fit(i, kind));
      ASSERT_TRUE(r.status.is_converged()) << r.status.text();
      const double expected = closed_form_cut_force(i, kind), got = ring_cut_force(r);
      const double peak = r.contacts.front().report.max_pressure;
      std::printf("  %s, i = %.2f %%: p b %.6e (closed form %.6e, %+.4f %%), peak multiplier %+.4f %% of p / (1 + i)\n",
                  kind.c_str(), 100 * i, got, expected, 100 * (got / expected - 1),
                  100 * (peak * (1 + i) / expected - 1));
      EXPECT_NEAR(got, expected, 5e-3 * expected) << kind << " i = " << i;
      EXPECT_NEAR(peak, expected / (1 + i), 5e-3 * expected) << kind << " i = " << i;
    }
}

TEST(Interference, LargeDeformationPressFitConverges) {
  {  // the small-interference limit: the linear closed form
    const RunResult r = run(press_fit(0.0015, "plane_stress", "neo_hookean"));
    ASSERT_TRUE(r.status.is_converged()) << r.status.text();
    EXPECT_NEAR(ring_cut_force(r), closed_form_cut_force(0.0015, "plane_stress"),
                5e-3 * closed_form_cut_force(0.0015, "plane_stress"));
  }
  for (const std::string kind : {"plane_stress", "plane_strain"}) {  // 5 % of the face's size (1.414)
    const Model m = build_model(read_case_text(press_fit(0.07, kind, "neo_hookean"), "press_fit.toml"));
    const RunResult r = solve_model(m, quiet_run());
    ASSERT_TRUE(r.status.is_converged()) << kind << ": " << r.status.text();
    const double linear = closed_form_cut_force(0.07, kind), got = ring_cut_force(r);
    std::printf("  Neo-Hookean %s, i = 7 %%: p b %.5e, %d load steps (linear closed form %.5e)\n", kind.c_str(), got,
                r.load_steps ? int(r.load_steps->steps.size()) : 0, linear);
    EXPECT_NEAR(got, linear, 0.1 * linear) << "finite strain: near the linear value, not equal";
  }
}

TEST(Interference, FrictionChangesNothingInARadialFit) {
  const double frictionless = ring_cut_force(run(press_fit(0.01)));
  const RunResult r = run(press_fit(0.01, "plane_stress", "linear_elastic", "friction = 0.1"));
  ASSERT_TRUE(r.status.is_converged()) << r.status.text();
  EXPECT_NEAR(ring_cut_force(r), frictionless, 1e-6 * frictionless);
  const RunResult nh = run(press_fit(0.01, "plane_stress", "neo_hookean", "friction = 0.1"));
  const double nh_frictionless = ring_cut_force(run(press_fit(0.01, "plane_stress", "neo_hookean")));
  ASSERT_TRUE(nh.status.is_converged()) << nh.status.text();
  EXPECT_NEAR(ring_cut_force(nh), nh_frictionless, 1e-6 * nh_frictionless);
}

// 3D, against a rigid obstacle: a sphere octant held on its top face, with
// the plane below it raised by d into it (interference = true), ends where
// the same plane moved up by d from touching ends: a frictionless elastic
// body has one equilibrium there, whatever the path (the gaps along the
// way differ: t (g - d) against g - t d).  Small deformation to round-off,
// Neo-Hookean to the Newton tolerance.
std::string octant(const std::string& law, const std::string& obstacle) {
  return "name = \"octant\"\n[geometry]\nshape = \"sphere_octant\"\nradius = 1.0\n[mesh]\ndegree = 2\n"
         "elements = [6, 2, 6]\n[material]\nmodel = \"" + law + "\"\nE = 1.0\nnu = 0.3\n"
         "[[dirichlet]]\nfaces = [\"left\"]\ncomponent = \"x\"\n[[dirichlet]]\nfaces = [\"back\"]\ncomponent = \"y\"\n"
         "[[dirichlet]]\nfaces = [\"top\"]\ncomponent = \"z\"\n[loading]\nsteps = 4\n"
         "[contact]\nface = \"curved\"\n" + obstacle + "[contact.obstacle]\ntype = \"plane\"\nnormal = [0.0, 0.0, 1.0]\n";
}

TEST(Interference, AnOverlapWithAnObstacleEndsWhereTheObstacleMovedThereEnds) {
  constexpr double d = 0.05;  // the pole's multiplier averages the gap over its support: it needs a few element heights
  for (const std::string law : {"linear_elastic", "neo_hookean"}) {
    const RunResult fit = run(octant(law, "interference = true\n") + "point = [0.0, 0.0, " + std::to_string(-1 + d) + "]\n");
    const RunResult moved =
        run(octant(law, "") + "point = [0.0, 0.0, -1.0]\nmotion = [0.0, 0.0, " + std::to_string(d) + "]\n");
    ASSERT_TRUE(fit.status.is_converged()) << fit.status.text();
    ASSERT_TRUE(moved.status.is_converged()) << moved.status.text();
    const double a = fit.contacts.front().report.total_force, b = moved.contacts.front().report.total_force;
    std::printf("  %s octant, overlap %.2f: force %.12g, moved plane %.12g\n", law.c_str(), d, a, b);
    EXPECT_GT(b, 1e-3);
    EXPECT_NEAR(a, b, (law == "linear_elastic" ? 1e-10 : 1e-7) * b) << law;
    EXPECT_NEAR((fit.u - moved.u).cwiseAbs().maxCoeff(), 0.0, (law == "linear_elastic" ? 1e-12 : 1e-9)) << law;
  }
}

TEST(Interference, AnUndeclaredOverlapIsAnErrorNamingTheKey) {
  std::string text = press_fit(0.0015);
  text.replace(text.find("interference = true"), 19, "");
  try {
    build_model(read_case_text(text, "press_fit.toml"));
    ADD_FAILURE() << "an overlap of 0.15 % was accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("press_fit.toml:"), std::string::npos) << message;
    EXPECT_NE(message.find("interference = true"), std::string::npos) << message;
    EXPECT_NE(message.find("= 0.00142"), std::string::npos) << "the threshold as a length: " << message;
  }
  EXPECT_THROW(read_case_text(press_fit(0.0015, "plane_stress", "linear_elastic", "law = \"tied\""), "press_fit.toml"),
               InputError);
}

}  // namespace
}  // namespace igac
