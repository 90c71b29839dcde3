// SPDX-License-Identifier: BSD-3-Clause
// Several bodies in one case ([[body]] tables, docs/case_file.md): each with
// its own geometry, mesh and material.  cases/roller_on_block.toml presses
// the hertz2d roller (E = 1) on an elastic block (E = 3); Hertz between two
// elastic bodies adds their compliances, 1/E* = (1 - nu1^2)/E1 + (1 -
// nu2^2)/E2, so with one nu the pair is a roller of modulus E1 E2 / (E1 +
// E2) on a rigid plane.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "contact/pressure.hpp"
#include "io/case_file.hpp"
#include "model/field_recovery.hpp"
#include "model/model.hpp"
#include "model/references.hpp"
#include "model/solve.hpp"
#include "tests/support/igac_process.hpp"

namespace igac {
namespace {

namespace fs = std::filesystem;
const fs::path kCases = fs::path(IGAC_SOURCE_DIR) / "cases";
constexpr double R = 1, P = 0.003, nu = 0.3;
// p0 against Hertz: the 1 %; measured -0.18 % (E2 = 3).
constexpr double kPeakTolerance = 0.01;

// cases/roller_on_block.toml with the two moduli replaced.
CaseSpec roller_on_block(const std::string& E_roller, const std::string& E_block, const std::string& dir_name) {
  std::string text = igac_test::read_file(kCases / "roller_on_block.toml");
  const std::string first = "E = 1.0", second = "E = 3.0";
  const size_t a = text.find(first), b = text.find(second);
  EXPECT_NE(a, std::string::npos);
  EXPECT_NE(b, std::string::npos);
  text.replace(b, second.size(), "E = " + E_block);
  text.replace(a, first.size(), "E = " + E_roller);
  const fs::path dir = fs::temp_directory_path() / dir_name;
  fs::create_directories(dir);
  std::ofstream(dir / "case.toml") << text;
  return read_case((dir / "case.toml").string());
}

// The spacing of the multipliers where the contact zone ends: the distance
// between the two anchors around r = a.
double spacing_at(const PressureReport& rep, double a) {
  double h = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k + 1 < rep.multipliers.size(); ++k) {
    const double r0 = rep.multipliers[k].r, r1 = rep.multipliers[k + 1].r;
    if (std::min(r0, r1) <= a && a <= std::max(r0, r1)) h = std::abs(r1 - r0);
  }
  return h;
}

struct Pair {
  PressureReport report;
  double applied = 0;
};

Pair solve_pair(const CaseSpec& spec) {
  const Model m = build_model(spec);
  const RunResult r = solve_model(m);
  EXPECT_EQ(r.status, "converged");
  EXPECT_EQ(r.contacts.size(), 1u);
  return {r.contacts.at(0).report, r.applied_force};
}

TEST(SeveralBodies, RollerOnAStifferBlockMatchesHertzWithTheCombinedModulus) {
  const Pair p = solve_pair(roller_on_block("1.0", "3.0", "igac_roller_on_block"));
  const HertzSolution pair = hertz_cylinder(R, P, 1.0 * 3.0 / (1.0 + 3.0), nu), rigid = hertz_cylinder(R, P, 1.0, nu);
  EXPECT_NEAR(p.report.total_force, P * R, 1e-12);  // the quarter's load, through the contact
  EXPECT_NEAR(p.report.max_pressure / pair.p0, 1.0, kPeakTolerance);
  EXPECT_NEAR(p.report.half_width, pair.a, spacing_at(p.report, pair.a));
  EXPECT_GT(std::abs(p.report.max_pressure - rigid.p0), 0.1 * rigid.p0);  // the block's compliance is seen
}

TEST(SeveralBodies, EachBodyKeepsItsOwnModulus) {
  // The moduli swapped: the same E*, so the same Hertz pressure.  Had one
  // modulus served both bodies, E* would be 1.5 or 0.5 (p0 off by 41 %).
  const Pair p = solve_pair(roller_on_block("3.0", "1.0", "igac_block_on_roller"));
  const HertzSolution pair = hertz_cylinder(R, P, 0.75, nu);
  EXPECT_NEAR(p.report.max_pressure / pair.p0, 1.0, kPeakTolerance);
  EXPECT_NEAR(p.report.half_width, pair.a, spacing_at(p.report, pair.a));
}

TEST(SeveralBodies, AStiffBlockApproachesTheRigidPlane) {
  const Pair p = solve_pair(roller_on_block("1.0", "1e4", "igac_roller_on_stiff_block"));
  const HertzSolution rigid = hertz_cylinder(R, P, 1.0, nu);
  EXPECT_NEAR(p.report.max_pressure / rigid.p0, 1.0, kPeakTolerance);
  EXPECT_NEAR(p.report.half_width, rigid.a, spacing_at(p.report, rigid.a));
}

TEST(SeveralBodies, OneBodyTableNamesItsFacesThroughItsBody) {
  // A case of a single [[body]] table: its faces are "roller:...", as with
  // several (the parametric names too), not the bare patch sides.
  CaseSpec spec = roller_on_block("1.0", "3.0", "igac_one_body_table");
  spec.bodies.resize(1);
  spec.contacts.clear();
  spec.dirichlet = {{{"roller:left"}, 0, 0.0}, {{"roller:curved"}, 1, 0.0}};
  const Model m = build_model(spec);
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_EQ(find_faces(m, "roller:curved"), find_faces(m, "roller:0:south"));
  EXPECT_EQ(find_faces(m, "roller:curved"), find_faces(m, "roller:v0"));
  EXPECT_FALSE(find_faces(m, "0:south"));
}

TEST(SeveralBodies, BodiesOfDifferentDegreesAreOneModel) {
  // The block cubic, the roller quadratic: one body of both degrees; the
  // roller's multipliers stay N2/S0 (its own degree), the block's
  // elements have their own size in the assembly, and the output mesh is
  // the block's at its degree and the roller's elevated to it, exactly.
  CaseSpec spec = roller_on_block("1.0", "3.0", "igac_roller_on_cubic_block");
  spec.bodies[1].degree = 3;
  const Model m = build_model(spec);
  EXPECT_EQ(m.body.patch(0).degree(0), 2);
  EXPECT_EQ(m.body.patch(1).degree(0), 3);
  EXPECT_EQ(m.contacts.at(0).face->num_multipliers(), 64);
  const RunResult r = solve_model(m);
  ASSERT_EQ(r.status, "converged");
  const PressureReport& rep = r.contacts.at(0).report;
  const HertzSolution pair = hertz_cylinder(R, P, 0.75, nu);
  EXPECT_NEAR(rep.max_pressure / pair.p0, 1.0, kPeakTolerance);
  EXPECT_NEAR(rep.half_width, pair.a, spacing_at(rep, pair.a));
  const BezierMesh mesh = body_bezier_mesh(m.body, r.u);
  ASSERT_EQ(mesh.num_elements(), m.body.num_elements());
  EXPECT_EQ(mesh.degree(0), 3);
  // The roller's lowest point, on its elevated first element, moved as the
  // quadratic roller does.
  const BezierElement& first = mesh.element(0);
  Eigen::VectorXd R0, at{{0.0, 0.0}};
  mesh.basis(first, at, R0, nullptr);
  const Eigen::RowVectorXd u_elevated = R0.transpose() * first.fields[0];
  EXPECT_NEAR((u_elevated - r.u.row(0)).norm(), 0.0, 1e-14);
}

TEST(SeveralBodies, FacesAreNamedByBodyAndRefineAddsToEveryBodysMesh) {
  CaseSpec spec = roller_on_block("1.0", "3.0", "igac_roller_on_block_names");
  const Model m = build_model(spec);
  ASSERT_EQ(m.parts.size(), 2u);
  EXPECT_EQ(m.parts[1].name, "block");
  EXPECT_EQ(m.parts[1].first_patch, 1);
  // The shape's names and the parametric ones, each body numbering its own patches.
  EXPECT_EQ(find_faces(m, "roller:curved"), find_faces(m, "roller:0:south"));
  EXPECT_EQ(find_faces(m, "block:top"), find_faces(m, "block:v1"));
  EXPECT_EQ(find_faces(m, "block:top")->front().patch, 1);
  EXPECT_FALSE(find_faces(m, "1:north"));  // several bodies: a face names its body
  EXPECT_FALSE(find_faces(m, "wheel:curved"));
  // The materials per patch: the roller's E = 1, the block's E = 3.
  const std::vector<LinearElastic> mats = m.patch_materials();
  ASSERT_EQ(mats.size(), 2u);
  EXPECT_NEAR(mats[1].mu() / mats[0].mu(), 3.0, 1e-12);
  const int elements = m.body.num_elements();
  spec.refine = 1;  // --refine 1: every body once finer than its [mesh]
  EXPECT_EQ(build_model(spec).body.num_elements(), 4 * elements);
}

TEST(SeveralBodies3D, SphereOnABlockMatchesHertzWithTheCombinedModulus) {
  // cases/sphere_on_block.toml: the 3 % for a and p0 in 3D, at a
  // mesh that runs in under a minute (measured p0 +0.19 %, a -2.2 %).
  constexpr double kHertz3D = 0.03;
  const Model m = build_model(read_case((kCases / "sphere_on_block.toml").string()));
  const RunResult r = solve_model(m);
  ASSERT_EQ(r.status, "converged");
  const PressureReport& rep = r.contacts.at(0).report;
  const HertzSolution pair = hertz_sphere(R, 1e-4, 0.75, nu);
  EXPECT_NEAR(rep.total_force / r.applied_force, 1.0, 1e-12);  // the octant's load, through the contact
  EXPECT_NEAR(rep.max_pressure / pair.p0, 1.0, kHertz3D);
  EXPECT_NEAR(rep.half_width / pair.a, 1.0, kHertz3D);
}

}  // namespace
}  // namespace igac
