// SPDX-License-Identifier: BSD-3-Clause
// Part of a side, [faces.NAME] side = "...", range = [from, to]
// (model/partial_faces.hpp): the patch is cut where the range ends and the
// name stands for the pieces' sides.
//  - a pressure on part of a block's top is carried whole by the supports
//    (p times the part's length, area in 3D) to round-off;
//  - a uniform pressure on three parts that tile the top is the patch test:
//    the homogeneous field at every control point to round-off, so the cut
//    pieces still make one body;
//  - a support on part of a side holds only its part;
//  - Hertz with its multipliers on the part of the curved face around the
//    contact zone gives the whole face's p0, a and force, in small and
//    large deformation, with fewer multipliers;
//  - a mirrored shape's range is the shape's own (before the mirror);
//  - the engine's cut pairs a seam's pieces and refuses a cut that would
//    leave a side joined to part of another;
//  - wrong ranges and sides are one-line errors naming the key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/geometry/patch_partition.hpp"
#include "engine/geometry/shapes.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/case_texts.hpp"
#include "tests/support/two_d_models.hpp"

namespace igac {
namespace {

const std::string kPath = std::string(IGAC_SOURCE_DIR) + "/cases/partial.toml";

// A 2 x 1 block (plane strain, E = 1, nu = 0.3), 8 x 4 elements of degree
// 2, with `rest` (its supports and loads) appended.
std::string free_block(const std::string& rest) { return igac_test::rectangle_case(2.0, 1.0, 8, 4) + rest; }

// The block on rollers (bottom: y held, left: x held), with `extra` appended.
std::string block(const std::string& extra) {
  return free_block(igac_test::rollers() + extra);
}

struct SolvedCase {
  Model model;
  RunResult result;
};

// `text` with the first `from` replaced by `to`.
void replace_once(std::string& text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
}

SolvedCase run(const std::string& text) {
  SolvedCase r{build_model(read_case_text(text, kPath)), {}};
  r.result = solve_model(r.model, quiet_run());
  return r;
}

Eigen::VectorXd reaction(const SolvedCase& r, const std::string& face) {
  for (const FaceReaction& f : r.result.dirichlet_reactions)
    if (f.face == face) return f.force;
  ADD_FAILURE() << "no reaction of " << face;
  return {};
}

TEST(PartialFaces, PressureOnPartOfTheTopIsCarriedByTheSupports) {
  // 0.3 and 0.6 are no knots of the 8 spans: the cut inserts them.
  for (const char* range : {"[0.25, 0.75]", "[0.3, 0.6]", "[0.0, 0.3]"}) {
    const SolvedCase r = run(block(std::string("[faces.loaded]\nside = \"top\"\nrange = ") + range +
                                  "\n[[pressure]]\nfaces = [\"loaded\"]\nvalue = 0.01\n"));
    double from = 0, to = 0;
    std::sscanf(range, "[%lf, %lf]", &from, &to);
    const double length = 2.0 * (to - from);  // the top runs over x in [0, 2]
    EXPECT_NEAR(reaction(r, "bottom")[1], 0.01 * length, 1e-14) << range;
    EXPECT_NEAR(reaction(r, "left")[0], 0.0, 1e-14) << range;
  }
}

TEST(PartialFaces, ThreePartsTilingTheTopPassThePatchTest) {
  const SolvedCase r = run(block(R"(
[faces.a]
side = "top"
range = [0.0, 0.3]
[faces.b]
side = "top"
range = [0.3, 0.7]
[faces.c]
side = "top"
range = [0.7, 1.0]
[[pressure]]
faces = ["a", "b", "c"]
value = 0.01
)"));
  // Plane strain, sigma_yy = -p, sigma_xx = 0: eps_yy = -p (1 - nu^2) / E,
  // eps_xx = p nu (1 + nu) / E; x held at x = 0, y at y = 0.
  const double p = 0.01, nu = 0.3;
  Eigen::Matrix2d G = Eigen::Matrix2d::Zero();
  G(0, 0) = p * nu * (1 + nu);
  G(1, 1) = -p * (1 - nu * nu);
  EXPECT_LT(igac_test::homogeneous_field_error(r.model.body, r.result.u, G), 1e-14);
  EXPECT_EQ(r.model.body.num_patches(), 3);
}

TEST(PartialFaces, ASupportOnPartOfASideHoldsOnlyThatPart) {
  // The block pulled up by a traction on its top, held in y on the middle
  // half of its bottom only: the control points of the bottom's other
  // pieces move, the held ones do not, and the support carries the load.
  const SolvedCase r = run(free_block(R"(
[faces.foot]
side = "bottom"
range = [0.25, 0.75]
[[dirichlet]]
faces = ["foot"]
component = "y"
[[dirichlet]]
faces = ["left"]
component = "x"
[[traction]]
faces = ["top"]
value = [0.0, 0.01]
)"));
  EXPECT_NEAR(reaction(r, "foot")[1], -0.02, 1e-14);
  double held = 0, moved = 0;
  for (int a = 0; a < r.model.body.num_control_points(); ++a) {
    const Eigen::Vector2d X = r.model.body.points().row(a).head(2).transpose();
    if (std::abs(X[1]) > 1e-12) continue;
    (X[0] >= 0.5 - 1e-12 && X[0] <= 1.5 + 1e-12 ? held : moved) += std::abs(r.result.u(a, 1));
  }
  EXPECT_EQ(held, 0.0);
  EXPECT_GT(moved, 1e-3);
}

TEST(PartialFaces, BoxTopPartCarriesPressureTimesItsArea) {
  const SolvedCase r = run(R"(
[geometry]
shape = "box"
size = [1.0, 1.0, 1.0]
[mesh]
degree = 2
elements = [4, 4, 2]
[material]
model = "linear_elastic"
E = 1.0
nu = 0.3
[faces.patch]
side = "w1"
range = [[0.25, 0.75], [0.0, 0.5]]
[[dirichlet]]
faces = ["w0"]
component = "z"
[[dirichlet]]
faces = ["u0"]
component = "x"
[[dirichlet]]
faces = ["v0"]
component = "y"
[[pressure]]
faces = ["patch"]
value = 0.01
)");
  EXPECT_NEAR(reaction(r, "w0")[2], 0.01 * 0.5 * 0.5, 1e-14);
}

// A Hertz case with its contact face cut to `range` of the curved side
// (the contact zone lies in it).
std::string hertz_on_part(const std::string& text, const std::string& range) {
  std::string s = text;
  replace_once(s, "face = \"curved\"", "face = \"near_contact\"");
  return s + "\n[faces.near_contact]\nside = \"curved\"\nrange = " + range + "\n";
}

// The case and its contact on part of the curved face give the same p0, a
// and force: the cut lowers the continuity outside the contact zone only,
// and what the spaces differ in there is `tolerance`.
void expect_same_contact(const std::string& text, const std::string& range, double tolerance) {
  const Model whole = build_model(read_case_text(text, kPath));
  const Model part = build_model(read_case_text(hertz_on_part(text, range), kPath));
  EXPECT_LT(part.num_multipliers(), whole.num_multipliers());
  const RunResult a = solve_model(whole, quiet_run()), b = solve_model(part, quiet_run());
  ASSERT_FALSE(a.contacts.empty());
  ASSERT_FALSE(b.contacts.empty());
  const auto &x = a.contacts.front().report, &y = b.contacts.front().report;
  std::printf("  whole face %d multipliers, part %d: p0 %.6g / %.6g, a %.6g / %.6g, force %.6g / %.6g\n",
              whole.num_multipliers(), part.num_multipliers(), x.max_pressure, y.max_pressure, x.half_width,
              y.half_width, x.total_force, y.total_force);
  EXPECT_NEAR(y.max_pressure, x.max_pressure, tolerance * x.max_pressure);
  EXPECT_NEAR(y.half_width, x.half_width, tolerance * x.half_width);
  EXPECT_NEAR(y.total_force, x.total_force, tolerance * x.total_force);
}

TEST(PartialFaces, HertzOnPartOfTheCurvedFaceIsHertz) {
  // cases/hertz2d.toml: a = 0.083 lies in the first 4 % of u.
  expect_same_contact(igac_test::shipped_case("hertz2d.toml"), "[0.0, 0.08]", 1e-4);
}

TEST(PartialFaces, LargeDeformationHertzOnPartOfTheCurvedFaceIsHertz) {
  // P = 0.1, Neo-Hookean, follower pressure: a = 0.55; on a coarser mesh.
  std::string text = igac_test::shipped_case("hertz2d_neohookean_pressure.toml");
  replace_once(text, "elements = [64, 16]", "elements = [32, 8]");
  expect_same_contact(text, "[0.0, 0.6]", 1e-3);
}

TEST(PartialFaces, FrictionalRollerOnBlockOnPartsOfBothFaces) {
  // cases/roller_on_block.toml with friction 0.2, the slave (roller) and the
  // master (block) faces each cut near the contact point: the same normal
  // and tangential forces, with the multipliers on the slave's part only.
  std::string whole = igac_test::shipped_case("roller_on_block.toml");
  replace_once(whole, "master = \"block:top\"", "master = \"block:top\"\nfriction = 0.2");
  std::string part = whole;
  replace_once(part, "face = \"roller:curved\"", "face = \"slave_part\"");
  replace_once(part, "master = \"block:top\"", "master = \"master_part\"");
  part += "\n[faces.slave_part]\nside = \"roller:curved\"\nrange = [0.0, 0.08]\n"
          "[faces.master_part]\nside = \"block:top\"\nrange = [0.0, 0.1]\n";
  const SolvedCase a = run(whole), b = run(part);
  EXPECT_LT(b.model.num_multipliers(), a.model.num_multipliers());
  ASSERT_EQ(a.result.reactions.size(), 1u);
  ASSERT_EQ(b.result.reactions.size(), 1u);
  const ObstacleReaction &x = a.result.reactions.front(), &y = b.result.reactions.front();
  std::printf("  normal force %.10g / %.10g, tangential %.10g / %.10g\n", x.normal_force, y.normal_force,
              x.tangential_force.norm(), y.tangential_force.norm());
  EXPECT_NEAR(y.normal_force, x.normal_force, 1e-9 * x.normal_force);
  EXPECT_GT(x.tangential_force.norm(), 0.1 * 0.2 * x.normal_force) << "friction carries a share";
  EXPECT_NEAR(y.tangential_force.norm(), x.tangential_force.norm(), 1e-4 * x.tangential_force.norm());
}

TEST(PartialFaces, AMirroredShapesRangeIsTheShapesOwn) {
  // Mirrored across x = 0 the block lies over x in [-2, 0]; the range
  // [0, 0.25] of its top is where the shape's own top starts, x in [-0.5, 0].
  std::string text = block("[faces.loaded]\nside = \"top\"\nrange = [0.0, 0.25]\n");
  replace_once(text, "shape = \"rectangle\"", "shape = \"rectangle\"\nmirror = \"x\"");
  const Model m = build_model(read_case_text(text, kPath));
  ASSERT_FALSE(m.reoriented_patches.empty()) << "the mirrored block runs its u backwards";
  const auto sides = find_faces(m, "loaded");
  ASSERT_TRUE(sides);
  ASSERT_EQ(sides->size(), 1u);
  for (int a : m.body.side_control_points(sides->front())) {
    EXPECT_GE(m.body.points()(a, 0), -0.5 - 1e-12);
    EXPECT_LE(m.body.points()(a, 0), 1e-12);
    EXPECT_NEAR(m.body.points()(a, 1), 1.0, 1e-12);
  }
}

// Two unit squares side by side, joined along x = 1.
std::vector<NurbsPatch> two_squares(std::vector<PatchInterface>& interfaces) {
  const NurbsPatch square = rectangle(1.0, 1.0).patch;
  Eigen::MatrixXd shifted = square.points();
  shifted.col(0).array() += 1.0;
  interfaces = {{PatchSide{0, Face{0, true}}, PatchSide{1, Face{0, false}}}};
  return {square, NurbsPatch(square.all_knots(), shifted, square.weights())};
}

TEST(PartialFaces, TwoPatchesCutAlikeArePairedPieceByPiece) {
  std::vector<PatchInterface> interfaces;
  std::vector<NurbsPatch> patches = two_squares(interfaces);
  PatchCuts cut0{0, {}}, cut1{1, {}};
  cut0.at[1] = {0.5};
  cut1.at[1] = {0.5};
  const auto pieces = cut_patches(patches, interfaces, {cut0, cut1});
  EXPECT_EQ(patches.size(), 4u);
  ASSERT_EQ(pieces[0].size(), 2u);
  EXPECT_EQ(interfaces.size(), 4u);  // two across x = 1, one at each cut
  const Body body(patches, interfaces);
  EXPECT_EQ(body.parts(), std::vector<int>(4, 0)) << "one body";
  EXPECT_EQ(body.num_control_points(), 3 * 3) << "bilinear pieces sharing their sides";
}

TEST(PartialFaces, ACutThatLeavesASideJoinedToPartOfAnotherIsRefused) {
  std::vector<PatchInterface> interfaces;
  std::vector<NurbsPatch> patches = two_squares(interfaces);
  PatchCuts cut{0, {}};
  cut.at[1] = {0.5};
  try {
    cut_patches(patches, interfaces, {cut});
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cut both patches"), std::string::npos) << e.what();
  }
}

void expect_refused(const std::string& text, const std::string& why) {
  try {
    build_model(read_case_text(text, kPath));
    ADD_FAILURE() << "accepted; expected: " << why;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(why), std::string::npos) << message;
    EXPECT_NE(message.find("partial.toml:"), std::string::npos) << "names the line: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  }
}

TEST(PartialFaces, WrongRangesAndSidesAreOneLineErrors) {
  expect_refused(block("[faces.x]\nside = \"top\"\nrange = [0.5, 0.25]\n"), "0 <= from < to <= 1");
  expect_refused(block("[faces.x]\nside = \"top\"\nrange = [0.5, 1.5]\n"), "0 <= from < to <= 1");
  expect_refused(block("[faces.x]\nside = \"top\"\nrange = 0.5\n"), "must be [from, to]");
  expect_refused(block("[faces.x]\nside = \"top\"\n"), "must be [from, to]");
  expect_refused(block("[faces.x]\nside = \"lid\"\nrange = [0, 0.5]\n"), "unknown side 'lid'");
  expect_refused(block("[faces.x]\nside = \"top\"\nrange = [0, 0.5]\nwhere = 1\n"), "unknown key");
  expect_refused(block("[faces.top2]\nside = \"top\"\nrange = [0, 0.5]\n[faces.x]\nside = \"top2\"\nrange = [0, 0.5]\n"),
                 "itself part of a side");
  expect_refused(block("[faces.right]\nside = \"top\"\nrange = [0, 0.5]\n"), "the name is taken");
}

}  // namespace
}  // namespace igac
