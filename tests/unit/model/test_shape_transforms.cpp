// SPDX-License-Identifier: BSD-3-Clause
// [geometry] scale, mirror, rotate (and translate): a body placed by exact
// affine maps of its control points (model/case_body.hpp).  The physics
// does not see where a body stands:
//  - cases/hertz2d.toml mirrored across x = 0 (the quarter disc turned
//    left-handed, run with its first direction backwards) and rotated by
//    90 degrees with its supports and obstacle turned alike give the same
//    peak pressure, half width and force as the case itself, to the solve's
//    round-off;
//  - a scaled body's Hertz reference reads the scaled radius;
//  - a box rotated about z and mirrored stands where the maps put it;
//  - wrong transforms are one-line errors.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "contact/pressure.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

std::string hertz2d() {
  std::ifstream in(std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void replace(std::string& text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
}

RunResult run(const std::string& text) {
  return solve_model(build_model(read_case_text(text, std::string(IGAC_SOURCE_DIR) + "/cases/placed.toml")), quiet_run());
}

// Round-off of a contact solve on this mesh: the factorisation sees the
// dofs in another order, so the last digits differ.
constexpr double kSameSolve = 1e-9;

void expect_same_contact(const RunResult& a, const RunResult& b) {
  ASSERT_FALSE(a.contacts.empty());
  ASSERT_FALSE(b.contacts.empty());
  const ContactResult &x = a.contacts.front(), &y = b.contacts.front();
  EXPECT_NEAR(x.report.max_pressure, y.report.max_pressure, kSameSolve * y.report.max_pressure);
  EXPECT_NEAR(x.report.half_width, y.report.half_width, kSameSolve * y.report.half_width);
  EXPECT_NEAR(x.report.total_force, y.report.total_force, kSameSolve * y.report.total_force);
  EXPECT_EQ(x.report.active, y.report.active);
}

TEST(ShapeTransforms, MirroredHertzIsHertz) {
  const RunResult plain = run(hertz2d());
  std::string text = hertz2d();
  replace(text, "radius = 1.0\n", "radius = 1.0\nmirror = \"x\"\n");
  const Model m = build_model(read_case_text(text, std::string(IGAC_SOURCE_DIR) + "/cases/placed.toml"));
  EXPECT_EQ(m.reoriented_patches, std::vector<int>{0});
  EXPECT_LT(m.body.points().col(0).maxCoeff(), 1e-15) << "the disc stands at x <= 0";
  expect_same_contact(solve_model(m, quiet_run()), plain);
}

TEST(ShapeTransforms, RotatedHertzIsHertz) {
  const RunResult plain = run(hertz2d());
  std::string text = hertz2d();
  // (x, y) -> (-y, x): the support on x = 0 is now on y = 0, the plane
  // y = -1 is now x = 1 with its normal turned.
  replace(text, "radius = 1.0\n", "radius = 1.0\nrotate = 90\n");
  replace(text, "component = \"x\"", "component = \"y\"");
  replace(text, "point = [0.0, -1.0]", "point = [1.0, 0.0]");
  replace(text, "normal = [0.0, 1.0]", "normal = [-1.0, 0.0]");
  expect_same_contact(run(text), plain);
}

TEST(ShapeTransforms, ScaledBodyReferenceReadsTheScaledRadius) {
  std::string text = hertz2d();
  replace(text, "radius = 1.0\n", "radius = 1.0\nscale = 2.0\n");
  replace(text, "point = [0.0, -1.0]", "point = [0.0, -2.0]");
  const RunResult r = run(text);
  ASSERT_TRUE(r.hertz);
  const HertzSolution expected = hertz_cylinder(2.0, 0.003, 1.0, 0.3);
  EXPECT_NEAR(r.hertz->a, expected.a, 1e-14);
  EXPECT_NEAR(r.hertz->p0, expected.p0, 1e-14);
  ASSERT_TRUE(r.pressure_error);
  EXPECT_LT(r.pressure_error->first / r.pressure_error->second, 0.05);
}

// A CaseSpec made in code gives the radius of the body as it stands (the
// reader's is scaled too): the shape is built from it once, not scaled twice.
TEST(ShapeTransforms, ScaledShapeMadeInCodeIsScaledOnce) {
  std::string text = hertz2d();
  replace(text, "radius = 1.0\n", "radius = 1.0\nscale = 2.0\n");
  CaseSpec spec = read_case_text(text, std::string(IGAC_SOURCE_DIR) + "/cases/placed.toml");
  EXPECT_EQ(spec.radius, 2.0);
  const double read = build_model(spec).body.points().col(0).maxCoeff();
  spec.shape_values.clear();  // as a program would give it: the named fields only
  EXPECT_EQ(build_model(spec).body.points().col(0).maxCoeff(), read);
  EXPECT_NEAR(read, 2.0, 1e-14);
}

TEST(ShapeTransforms, BoxStandsWhereTheMapsPutIt) {
  const std::string box =
      "name = \"placed\"\n[geometry]\nshape = \"box\"\nsize = [1.0, 2.0, 3.0]\nscale = 2.0\nmirror = [\"x\"]\n"
      "rotate = [0.0, 0.0, 90.0]\ntranslate = [10.0, 0.0, 0.0]\n[mesh]\ndegree = 1\nelements = [1, 1, 1]\n"
      "[material]\nE = 1.0\nnu = 0.3\n[[dirichlet]]\nfaces = [\"bottom\"]\ncomponent = \"z\"\n";
  const Model m = build_model(read_case_text(box, "placed.toml"));
  // scale 2: [0, 2] x [0, 4] x [0, 6]; mirror x: [-2, 0]; turn (x, y) -> (-y, x): x in [-4, 0],
  // y in [-2, 0]; translate: x in [6, 10].
  const Eigen::MatrixXd& X = m.body.points();
  EXPECT_NEAR(X.col(0).minCoeff(), 6.0, 1e-14);
  EXPECT_NEAR(X.col(0).maxCoeff(), 10.0, 1e-14);
  EXPECT_NEAR(X.col(1).minCoeff(), -2.0, 1e-14);
  EXPECT_NEAR(X.col(1).maxCoeff(), 0.0, 1e-14);
  EXPECT_NEAR(X.col(2).maxCoeff(), 6.0, 1e-14);
  EXPECT_EQ(m.reoriented_patches, std::vector<int>{0}) << "one mirror: left-handed";
  // The face names follow the body: "bottom" (z = 0) is still where z = 0.
  const std::vector<PatchSide> bottom = *find_faces(m, "bottom");
  ASSERT_EQ(bottom.size(), 1u);
  EXPECT_EQ(bottom.front().face.direction, 2);
  EXPECT_FALSE(bottom.front().face.at_end);
}

void expect_error(const std::string& text, const std::string& needle) {
  try {
    read_case_text(text, "placed.toml");
    ADD_FAILURE() << "accepted: " << needle;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(needle), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(ShapeTransforms, WrongTransformsAreOneLineErrors) {
  std::string text = hertz2d();
  replace(text, "radius = 1.0\n", "radius = 1.0\nmirror = \"z\"\n");
  expect_error(text, "[geometry] mirror: unknown axis 'z'");
  text = hertz2d();
  replace(text, "radius = 1.0\n", "radius = 1.0\nrotate = [0.0, 90.0]\n");
  expect_error(text, "[geometry] rotate: in 2D one angle");
  text = hertz2d();
  replace(text, "radius = 1.0\n", "radius = 1.0\nscale = -1.0\n");
  expect_error(text, "[geometry] scale");
}

}  // namespace
}  // namespace igac
