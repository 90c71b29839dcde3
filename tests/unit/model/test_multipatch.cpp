// SPDX-License-Identifier: BSD-3-Clause
// Multi-patch bodies (engine/body.hpp): patches joined C0 across conforming
// interfaces share the unknowns of their common control points.  Checked
// here: the numbering (identity for one patch, shared points once), the
// refusal of non-conforming interfaces naming both sides, a stiffness with
// exactly the rigid motions of ONE body in its kernel, nested-mesh errors at
// round-off for a field both meshes represent exactly, the 2D Hertz body as
// two patches (Hertz p0 within 1 %, force to 1e-10, the one-patch result
// within the discretisation error), Lame's optimal rates on a four-patch
// annulus, one ParaView grid with a continuous displacement, a contact face
// over two patches (3D block), and bad geometry files as one-line errors.
#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "engine/body.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/spline/refinement.hpp"
#include "engine/spline/split.hpp"
#include "io/gismo_xml.hpp"
#include "io/vtk_output.hpp"
#include "tests/support/igac_process.hpp"
#include "tests/support/vtu_file.hpp"

namespace igac {
namespace {

namespace fs = std::filesystem;
const std::string kSource = IGAC_SOURCE_DIR;

constexpr double kRoundOff = 1e-12;
constexpr double kRateBand = 0.2;  // as the one-patch Lame test

// The quarter disc as two sectors, both patches raised to degree p and cut
// into n0 x n1 uniform elements (patch 1's v direction into n1_second).
std::vector<NurbsPatch> two_sectors(int p, int n0, int n1, int n1_second = -1) {
  const MultiPatch mp = read_gismo_xml(kSource + "/tests/data/quarter_disc_two_patches.xml");
  std::vector<NurbsPatch> out;
  for (int k = 0; k < 2; ++k) {
    NurbsPatch q = elevate_to(mp.patches[k], p);
    q = refine_to(q, 0, KnotVector::uniform(p, n0));
    q = refine_to(q, 1, KnotVector::uniform(p, k == 1 && n1_second > 0 ? n1_second : n1));
    out.push_back(q);
  }
  return out;
}

std::vector<PatchInterface> two_sector_interface() {
  return read_gismo_xml(kSource + "/tests/data/quarter_disc_two_patches.xml").interfaces;
}

TEST(Body, OnePatchKeepsThePatchNumbering) {
  const NurbsPatch p = two_sectors(2, 3, 2).front();
  const Body b(p);
  ASSERT_EQ(b.num_control_points(), p.num_control_points());
  for (int i = 0; i < p.num_control_points(); ++i) EXPECT_EQ(b.body_cps(0)[i], i);
  EXPECT_EQ(b.points(), p.points());
}

TEST(Body, ConformingInterfaceSharesItsControlPoints) {
  const auto patches = two_sectors(2, 3, 4);
  const Body b(patches, two_sector_interface());
  const auto itf = two_sector_interface().front();
  const int shared = int(patches[0].face_control_points(itf.first.face).size());
  EXPECT_EQ(b.num_control_points(), patches[0].num_control_points() + patches[1].num_control_points() - shared);
  // Each body control point sits where every patch point numbered with it sits.
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < patches[k].num_control_points(); ++i)
      EXPECT_LE((b.points().row(b.body_cps(k)[i]) - patches[k].points().row(i)).norm(), kRoundOff);
  // The two sides name the same body control points (as sets).
  auto a = b.side_control_points(itf.first), c = b.side_control_points(itf.second);
  std::sort(a.begin(), a.end());
  std::sort(c.begin(), c.end());
  EXPECT_EQ(a, c);
}

TEST(Body, OtherKnotsOnTheInterfaceAreRefusedNamingBothSides) {
  try {
    const Body b(two_sectors(2, 3, 4, 5), two_sector_interface());
    FAIL() << "a non-conforming interface was accepted";
  } catch (const BodyError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("patch 0 (east)"), std::string::npos) << what;
    EXPECT_NE(what.find("patch 1 (west)"), std::string::npos) << what;
    EXPECT_NE(what.find("not conforming"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
}

TEST(Body, SidesThatDoNotMeetAreRefused) {
  auto patches = two_sectors(2, 3, 4);
  Eigen::MatrixXd moved = patches[1].points();
  moved.col(0).array() += 1e-3;
  patches[1] = NurbsPatch(patches[1].all_knots(), moved, patches[1].weights());
  EXPECT_THROW(Body(patches, two_sector_interface()), BodyError);
}

// Joined patches are one body: with no Dirichlet condition the stiffness has
// the 3 rigid motions of one 2D body in its kernel (two loose patches: 6).
TEST(Body, StiffnessKernelIsTheRigidMotionsOfOneBody) {
  const Body b(two_sectors(2, 2, 2), two_sector_interface());
  const DofMap dofs(b, {});
  const LinearSystem s = assemble_linear_elasticity(b, dofs, LinearElastic(1.0, 0.3), Eigen::VectorXd::Zero(2));
  const Eigen::MatrixXd K(s.K);
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K).eigenvalues();
  int zero = 0;
  for (int i = 0; i < ev.size(); ++i) zero += std::abs(ev[i]) < 1e-10 * ev.cwiseAbs().maxCoeff();
  EXPECT_EQ(zero, 3);
  EXPECT_EQ(free_rigid_modes(b, dofs).modes.cols(), 3);
}

// u_A = X_A is the identity map on both meshes (NURBS reproduce the
// geometry), so their difference vanishes: error norms at round-off, patch by
// patch.
TEST(Body, ErrorAgainstAFinerMultiPatchMeshIsRoundOffForAnExactField) {
  const Body coarse(two_sectors(2, 2, 2), two_sector_interface());
  const Body fine(two_sectors(2, 4, 6), two_sector_interface());
  const ErrorNorms e = errors_against_reference(coarse, coarse.points(), fine, fine.points(), 4);
  EXPECT_GT(e.ref_l2, 0.1);
  EXPECT_LE(e.l2, kRoundOff * e.ref_l2);
  EXPECT_LE(e.h1, kRoundOff * e.ref_h1);
}

RunResult run_case(CaseSpec spec, Model* keep = nullptr) {
  Model m = build_model(spec);
  RunResult r = solve_model(m, quiet_run());
  if (keep) *keep = std::move(m);
  return r;
}

TEST(MultiPatchHertz, TwoPatchesGiveHertzAndTheOnePatchResult) {
  Model m;
  const RunResult two = run_case(read_case(kSource + "/cases/hertz2d_two_patches.toml"), &m);
  const RunResult one = run_case(read_case(kSource + "/cases/hertz2d.toml"));
  ASSERT_EQ(two.status, "converged");
  ASSERT_EQ(m.body.num_patches(), 2);
  ASSERT_EQ(m.contacts.front().face->sides.size(), 2u);
  const double P = 0.003, R = 1.0;
  EXPECT_NEAR(two.contacts.front().report.total_force, P * R, 1e-10 * P * R);
  EXPECT_NEAR(two.applied_force, P * R, 1e-10 * P * R);
  EXPECT_NEAR(two.contacts.front().report.max_pressure, two.hertz->p0, 0.01 * two.hertz->p0);
  EXPECT_NEAR(two.contacts.front().report.half_width, two.hertz->a, 0.01 * two.hertz->a);
  // Within the discretisation error of the one-patch mesh (p0 -0.19 %, a
  // -0.76 % from Hertz; a is read at multiplier resolution): the two agree
  // to a fraction of it.
  EXPECT_NEAR(two.contacts.front().report.max_pressure, one.contacts.front().report.max_pressure,
              0.002 * one.contacts.front().report.max_pressure);
  EXPECT_NEAR(two.contacts.front().report.half_width, one.contacts.front().report.half_width, 0.002 * one.contacts.front().report.half_width);
  EXPECT_NEAR(two.pressure_error->first / two.pressure_error->second,
              one.pressure_error->first / one.pressure_error->second, 0.01);
}

struct Level {
  double h, l2, h1;
};

void expect_four_patch_lame_rates(int p) {
  CaseSpec spec = read_case(kSource + "/tests/data/lame_four_patches.toml");
  const int r0 = spec.refine;
  std::vector<Level> lv;
  for (int l = 0; l < 4; ++l) {
    apply_overrides(spec, p, r0 + l);
    Model m;
    const RunResult r = run_case(spec, &m);
    ASSERT_EQ(r.status, "converged");
    ASSERT_EQ(m.body.num_patches(), 4);
    ASSERT_TRUE(r.displacement_errors.has_value());
    lv.push_back({m.mesh_size, r.displacement_errors->l2, r.displacement_errors->h1});
  }
  const Level& a = lv[2];
  const Level& b = lv[3];
  EXPECT_NEAR(std::log2(a.l2 / b.l2), p + 1, kRateBand) << "L2 rate, should be about p+1";
  EXPECT_NEAR(std::log2(a.h1 / b.h1), p, kRateBand) << "H1 rate, should be about p";
  EXPECT_NEAR(std::log(a.l2 / b.l2) / std::log(a.h / b.h), p + 1, kRateBand);
  EXPECT_NEAR(std::log(a.h1 / b.h1) / std::log(a.h / b.h), p, kRateBand);
}

TEST(MultiPatchLame, FourPatchAnnulusKeepsOptimalRatesDegree2) { expect_four_patch_lame_rates(2); }
TEST(MultiPatchLame, FourPatchAnnulusKeepsOptimalRatesDegree3) { expect_four_patch_lame_rates(3); }

vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const fs::path& path) { return igac_test::read_vtu(path.string()); }

// One .vtu with every patch's Bezier cells; where cells of the two patches
// meet, their points coincide and carry the same displacement (C0).
TEST(MultiPatchVtk, OneGridWithEveryPatchAndAContinuousDisplacement) {
  CaseSpec spec = read_case(kSource + "/cases/hertz2d_two_patches.toml");
  spec.elements = {8, 4};
  Model m;
  const RunResult r = run_case(spec, &m);
  ASSERT_EQ(r.status, "converged");
  igac_test::TempDir tmp("mpvtk");
  const VtkStep step = write_vtk(tmp.path().string(), m, r, 0, 1.0);
  const auto body = read_vtu(tmp.path() / step.files.at(0));
  ASSERT_EQ(body->GetNumberOfCells(), m.body.num_elements());
  const auto contact = read_vtu(tmp.path() / step.files.at(1));
  EXPECT_EQ(contact->GetNumberOfCells(), 2 * 8);  // both arcs
  vtkDataArray* u = body->GetPointData()->GetArray("displacement");
  ASSERT_NE(u, nullptr);
  // Points of different cells at one place: same displacement.
  std::map<std::pair<long long, long long>, Eigen::Vector2d> seen;
  int matched = 0;
  double worst = 0;
  for (vtkIdType i = 0; i < body->GetNumberOfPoints(); ++i) {
    double x[3];
    body->GetPoint(i, x);
    const auto key = std::make_pair(std::llround(x[0] * 1e9), std::llround(x[1] * 1e9));
    const Eigen::Vector2d ui(u->GetComponent(i, 0), u->GetComponent(i, 1));
    if (auto it = seen.find(key); it != seen.end()) {
      worst = std::max(worst, (it->second - ui).norm());
      ++matched;
    } else {
      seen[key] = ui;
    }
  }
  EXPECT_GT(matched, 0);
  EXPECT_LE(worst, 1e-12 * r.u.cwiseAbs().maxCoeff());
}

// The ball touches the block on the interface of its two patches: the
// contact face spans both tops, both carry pressure, and by the mirror
// symmetry x -> 2 - x their shares of the force are equal.
TEST(MultiPatchContact, BallIndentsTwoPatchBlockAcrossTheInterface) {
  CaseSpec spec = read_case(kSource + "/cases/indented_block.toml");
  spec.elements = {6, 12, 3};
  Model m;
  const RunResult r = run_case(spec, &m);
  ASSERT_EQ(r.status, "converged");
  const ContactFace& cf = *m.contacts.front().face;
  ASSERT_EQ(cf.sides.size(), 2u);
  const auto& sol = r.contact->solution;
  std::array<double, 2> share{0, 0};
  for (int s = 0; s < 2; ++s)
    for (int k = 0; k < cf.sides[s].space.size(); ++k) {
      const int K = cf.sides[s].first_multiplier + k;
      share[s] -= sol.lambda[K] * r.contact->op.weights[K];
    }
  EXPECT_GT(share[0], 0);
  EXPECT_NEAR(share[0], share[1], 1e-8 * (share[0] + share[1]));
  EXPECT_NEAR(share[0] + share[1], r.reactions.front().normal_force, 1e-10 * r.reactions.front().normal_force);
  // The first contact point (1, 1, 1) is inside a side, not at a corner: the
  // half width is the reach of the pressed multipliers, about sqrt(R delta)
  // for a ball of radius R pressed delta into a half-space, to within one
  // face element (the multipliers' anchors sit at element centres).
  const double element = 1.0 / spec.elements[0], sqrt_R_delta = std::sqrt(0.5 * 0.1);
  EXPECT_NEAR(r.contacts.front().report.half_width, sqrt_R_delta, element);
}

// A contact face with a C0 knot inside it (a ring of one patch has four)
// was refused ("contact face knot 0.5 has multiplicity 3 > p-1 = 2"); its
// multipliers are now discontinuous there, so the one patch is the body of
// its two halves joined there: the same unknowns numbered otherwise, the
// same multipliers in the same order.  A block on a rigid disc whose
// contact zone spans the knot, p = 3 (S1 multipliers: the case where the
// knot changes the space).
TEST(MultiPatchContact, OnePatchWithAC0KnotIsTheTwoPatchBody) {
  igac_test::TempDir tmp("c0knot");
  // The degree-1 block with a knot at x = 0.5: C0 there once raised to p = 3.
  const NurbsPatch block = insert_knots(rectangle(1.0, 0.25).patch, 0, {0.5}).patch;
  const auto [left, right] = split_patch(block, 0, 0.5);
  write_gismo_xml(MultiPatch{{block}, {}, {}}, (tmp.path() / "one.xml").string());
  write_gismo_xml(MultiPatch{{normalised(left), normalised(right)}, {{PatchSide(0, Face{0, true}), PatchSide(1, Face{0, false})}}, {}},
                  (tmp.path() / "two.xml").string());
  const auto text = [](const std::string& file, const std::string& faces, const std::string& elements) {
    return "[geometry]\nfile = \"" + file + "\"\n[faces]\n" + faces + "[mesh]\ndegree = 3\nelements = " + elements +
           "\n[material]\nE = 1.0\nnu = 0.3\n[[dirichlet]]\nfaces = [\"left\"]\ncomponent = \"x\"\n"
           "[[pressure]]\nfaces = [\"top\"]\nvalue = 0.01\n[contact]\nface = \"bottom\"\n"
           "[contact.obstacle]\ntype = \"sphere\"\ncentre = [0.55, -2.0]\nradius = 2.0\n";
  };
  std::ofstream(tmp.path() / "one.toml") << text("one.xml",
      "left = [\"0:west\"]\ntop = [\"0:north\"]\nbottom = [\"0:south\"]\n", "[8, 2]");
  std::ofstream(tmp.path() / "two.toml") << text("two.xml",
      "left = [\"0:west\"]\ntop = [\"0:north\", \"1:north\"]\nbottom = [\"0:south\", \"1:south\"]\n", "[4, 2]");
  Model m1, m2;
  const RunResult one = run_case(read_case((tmp.path() / "one.toml").string()), &m1);
  const RunResult two = run_case(read_case((tmp.path() / "two.toml").string()), &m2);
  ASSERT_EQ(one.status, "converged");
  ASSERT_EQ(two.status, "converged");
  ASSERT_EQ(m1.contacts.front().face->sides.size(), 1u);
  const Eigen::VectorXd& l1 = one.contact->solution.lambda;
  const Eigen::VectorXd& l2 = two.contact->solution.lambda;
  ASSERT_EQ(l1.size(), l2.size());
  // The pressed multipliers lie on both sides of the knot.
  const auto& space = m1.contacts.front().face->sides.front().space;
  int below = 0, above = 0;
  for (int K = 0; K < l1.size(); ++K)
    if (l1[K] < 0) (space.anchor(K)[0] < 0.5 ? below : above) += 1;
  EXPECT_GT(below, 0);
  EXPECT_GT(above, 0);
  // The same linear systems up to the numbering: they differ by the
  // factorisations' round-off, about cond(K) eps (measured 1.2e-13).
  constexpr double kRenumbered = 1e-10;
  EXPECT_LE((l1 - l2).cwiseAbs().maxCoeff(), kRenumbered * l1.cwiseAbs().maxCoeff()) << l1.transpose();
  EXPECT_NEAR(one.reactions.front().normal_force, two.reactions.front().normal_force,
              kRenumbered * two.reactions.front().normal_force);
}

// Bad multi-patch geometry files: exit 2, one line naming the file, the
// patches and what is wrong, and no output folder.
fs::path two_patch_case(const fs::path& dir, const MultiPatch& body) {
  write_gismo_xml(body, (dir / "body.xml").string());
  std::string s = igac_test::read_file(kSource + "/cases/hertz2d_two_patches.toml");
  const std::string from = "file = \"quarter_disc_two_patches.xml\"";
  s.replace(s.find(from), from.size(), "file = \"body.xml\"");
  std::ofstream(dir / "case.toml") << s;
  return dir / "case.toml";
}

void expect_bad_file(const igac_test::TempDir& tmp, const std::vector<std::string>& parts) {
  const auto o = igac_test::run_igac("run case.toml --out result", tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  for (const auto& p : parts) EXPECT_NE(o.output.find(p), std::string::npos) << p << " in: " << o.output;
  EXPECT_FALSE(fs::exists(tmp.path() / "result"));
}

TEST(MultiPatchFiles, NonConformingInterfaceIsAOneLineErrorNamingBothSides) {
  igac_test::TempDir tmp("mpbad");
  MultiPatch body = read_gismo_xml(kSource + "/tests/data/quarter_disc_two_patches.xml");
  // Patch 1's side of the interface runs along the same radius as patch 0's
  // but at another speed (its middle control point moved along the line).
  // (A knot on one side only is no longer an error: the case inserts it in
  // the other side, test_conforming_interfaces.cpp.)
  Eigen::MatrixXd P = body.patches[1].points();
  P.row(3) *= 0.7;
  body.patches[1] = NurbsPatch(body.patches[1].all_knots(), P, body.patches[1].weights());
  two_patch_case(tmp.path(), body);
  expect_bad_file(tmp, {"body.xml", "patch 0 (east)", "patch 1 (west)", "not conforming"});
}

TEST(MultiPatchFiles, FoldedPatchIsAOneLineErrorNamingThePatch) {
  igac_test::TempDir tmp("mpfold");
  MultiPatch body = read_gismo_xml(kSource + "/tests/data/quarter_disc_two_patches.xml");
  // pull patch 1's middle control point across its arc: the map folds
  Eigen::MatrixXd pts = body.patches[1].points();
  pts.row(4) << 1.6, -0.9;
  body.patches[1] = NurbsPatch(body.patches[1].all_knots(), pts, body.patches[1].weights());
  two_patch_case(tmp.path(), body);
  expect_bad_file(tmp, {"body.xml", "patch 1 folds"});
}

}  // namespace
}  // namespace igac

namespace igac {
namespace {

// Without the mid-plane symmetry: half the O-ring's cross-section as two
// patches, a fixed plate below and a moving plate above, nothing else holding
// it vertically.  The two plates balance, and each carries what the plate of
// the symmetric quarter model (cases/oring.toml) carries.
TEST(MultiPatchORing, TwoPlatesOnTwoPatchesEqualTheSymmetricQuarter) {
  const RunResult half = run_case(read_case(kSource + "/cases/oring_two_plates.toml"));
  const RunResult quarter = run_case(read_case(kSource + "/cases/oring.toml"));
  ASSERT_EQ(half.status, "converged");
  ASSERT_EQ(quarter.status, "converged");
  ASSERT_EQ(half.reactions.size(), 2u);
  const double F = quarter.reactions.front().normal_force;
  EXPECT_GT(F, 0);
  EXPECT_NEAR(half.reactions[0].normal_force, half.reactions[1].normal_force, 1e-8 * F);
  EXPECT_NEAR(half.reactions[0].normal_force, F, 1e-6 * F);
}

}  // namespace
}  // namespace igac
