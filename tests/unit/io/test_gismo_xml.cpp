// SPDX-License-Identifier: BSD-3-Clause
// G+Smo XML geometry files (io/gismo_xml.hpp), patch splitting
// (engine/spline/split.hpp) and `igac geometry`.
//
// The checked-in bodies tests/data/quarter_disc.xml,
// tests/data/quarter_disc_two_patches.xml, tests/data/annulus_four_patches.xml
// and cases/indented_block.xml are made by make_bodies() below;
// GismoXmlData.CheckedInFilesAreTheGeneratedBodies checks them and, run as
//   IGAC_REGENERATE_XML=1 build/tests/igac_tests --gtest_filter='GismoXmlData.*'
// rewrites them first.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "engine/geometry/shapes.hpp"
#include "engine/spline/refinement.hpp"
#include "engine/spline/split.hpp"
#include "io/case_file.hpp"
#include "io/gismo_xml.hpp"

namespace {

namespace fs = std::filesystem;
using namespace igac;

// Numbers are written in their shortest round-trip form, so a file read back
// gives the same doubles; the bound leaves room for nothing but the last bit.
constexpr double kRoundTrip = 1e-15;
// Knot insertion is a sequence of convex combinations: its geometry agrees
// with the original to a few ulps of the coordinates (size ~1).
constexpr double kSplitTolerance = 1e-13;
// Exit code of igac for bad input (app/main.cpp).
constexpr int kBadInputExit = 2;

std::string source(const std::string& rel) { return std::string(IGAC_SOURCE_DIR) + "/" + rel; }

fs::path temp_dir(const std::string& tag) {
  fs::path p = fs::temp_directory_path() / ("igac_gismo_" + tag + "_" + std::to_string(getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
}

double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

void expect_same_patch(const NurbsPatch& a, const NurbsPatch& b, double tol, const std::string& what) {
  ASSERT_EQ(a.param_dim(), b.param_dim()) << what;
  ASSERT_EQ(a.space_dim(), b.space_dim()) << what;
  for (int d = 0; d < a.param_dim(); ++d) {
    EXPECT_EQ(a.degree(d), b.degree(d)) << what;
    ASSERT_EQ(a.knots(d).size(), b.knots(d).size()) << what;
    for (int i = 0; i < a.knots(d).size(); ++i) EXPECT_NEAR(a.knots(d)[i], b.knots(d)[i], tol) << what;
  }
  ASSERT_EQ(a.num_control_points(), b.num_control_points()) << what;
  EXPECT_LE(relative_difference(a.points(), b.points()), tol) << what;
  EXPECT_LE(relative_difference(a.weights(), b.weights()), tol) << what;
}

void expect_same_body(const MultiPatch& a, const MultiPatch& b, double tol, const std::string& what) {
  ASSERT_EQ(a.patches.size(), b.patches.size()) << what;
  for (size_t i = 0; i < a.patches.size(); ++i) expect_same_patch(a.patches[i], b.patches[i], tol, what + " patch " + std::to_string(i));
  ASSERT_EQ(a.interfaces.size(), b.interfaces.size()) << what;
  for (size_t k = 0; k < a.interfaces.size(); ++k) {
    EXPECT_TRUE(a.interfaces[k].first == b.interfaces[k].first) << what << " interface " << k;
    EXPECT_TRUE(a.interfaces[k].second == b.interfaces[k].second) << what << " interface " << k;
  }
  ASSERT_EQ(a.boundary.size(), b.boundary.size()) << what;
  for (size_t k = 0; k < a.boundary.size(); ++k) EXPECT_TRUE(a.boundary[k] == b.boundary[k]) << what;
}

PatchSide side(int patch, int gismo_side) { return PatchSide{patch, face_of_gismo_side(gismo_side)}; }

// ---------------------------------------------------------------- the bodies

// A patch cut at the middle of direction d, both halves back on [0, 1].
std::pair<NurbsPatch, NurbsPatch> halves(const NurbsPatch& p, int d) {
  auto [a, b] = split_patch(p, d, 0.5);
  return {normalised(a), normalised(b)};
}

// The Hertz quarter disc (radius 1, the region of shapes.cpp quarter_disc)
// cut along its 45 degree radius OM into two biquadratic patches, each an
// eighth of the disc: south (v = 0) the exact 45 degree arc (rational
// quadratic, middle weight cos 22.5 deg, Piegl & Tiller 7.5), the radius OM
// as patch 0's east and patch 1's west side (the same three control points,
// both running from M to O).  A three-sided region needs one straight corner
// per patch, kept away from the contact point as in quarter_disc: patch 0
// (A at u = v = 0, the contact point) has it at D = (0, -1/2) between west
// (A to D) and north (D to O) on x = 0; patch 1 at E = (1/2, 0) between east
// (B to E) and north (O to E) on y = 0.  Interior control points: the mean of
// the four edge-middle ones.
MultiPatch quarter_disc_two_sectors() {
  const double s = std::sqrt(0.5), t = std::sqrt(2.0) - 1, c = std::cos(M_PI / 8);
  const Eigen::Vector2d O(0, 0), A(0, -1), M(s, -s), B(1, 0), D(0, -0.5), E(0.5, 0);
  auto patch = [&](std::array<Eigen::Vector2d, 9> P) {
    P[4] = (P[1] + P[3] + P[5] + P[7]) / 4;
    Eigen::MatrixXd X(9, 2);
    for (int i = 0; i < 9; ++i) X.row(i) = P[i].transpose();
    Eigen::VectorXd w = Eigen::VectorXd::Ones(9);
    w[1] = c;
    return NurbsPatch({KnotVector::uniform(2, 1), KnotVector::uniform(2, 1)}, X, w);
  };
  const Eigen::Vector2d Z(0, 0);  // placeholder for the interior point
  MultiPatch body;
  body.patches = {patch({A, Eigen::Vector2d(t, -1), M, (A + D) / 2, Z, (M + O) / 2, D, (D + O) / 2, O}),
                  patch({M, Eigen::Vector2d(1, -t), B, (M + O) / 2, Z, (B + E) / 2, O, (O + E) / 2, E})};
  body.interfaces = {{side(0, 2), side(1, 1)}};
  body.boundary = {side(0, 1), side(0, 3), side(0, 4), side(1, 2), side(1, 3), side(1, 4)};
  return body;
}

std::map<std::string, MultiPatch> make_bodies() {
  std::map<std::string, MultiPatch> out;
  const NurbsPatch disc = quarter_disc(1.0).patch;
  out["tests/data/quarter_disc.xml"] = single_patch_body(disc);

  out["tests/data/quarter_disc_two_patches.xml"] = quarter_disc_two_sectors();

  // Lame's annulus 1 <= r <= 2 cut at the middle radius and at 45 degrees:
  // patch 0 (inner, bottom), 1 (outer, bottom), 2 (inner, top), 3 (outer, top);
  // the four meet at one interior point.
  MultiPatch ring;
  auto [inner, outer] = halves(quarter_annulus(1.0, 2.0).patch, 0);
  auto [p0, p2] = halves(inner, 1);
  auto [p1, p3] = halves(outer, 1);
  ring.patches = {p0, p1, p2, p3};
  ring.interfaces = {{side(0, 2), side(1, 1)}, {side(2, 2), side(3, 1)}, {side(0, 4), side(2, 3)}, {side(1, 4), side(3, 3)}};
  ring.boundary = {side(0, 1), side(0, 3), side(1, 2), side(1, 3), side(2, 1), side(2, 4), side(3, 2), side(3, 4)};
  out["tests/data/annulus_four_patches.xml"] = ring;

  // A block [0, 2] x [0, 2] x [0, 1] cut at x = 1, for a rigid sphere pressed
  // on its top face (w = 1, side 6) across the interface.
  MultiPatch block;
  auto [b0, b1] = halves(box(2.0, 2.0, 1.0).patch, 0);
  block.patches = {b0, b1};
  block.interfaces = {{side(0, 2), side(1, 1)}};
  block.boundary = {side(0, 1), side(0, 3), side(0, 4), side(0, 5), side(0, 6),
                    side(1, 2), side(1, 3), side(1, 4), side(1, 5), side(1, 6)};
  out["cases/indented_block.xml"] = block;
  return out;
}

// ---------------------------------------------------------------- splitting

TEST(SplitPatch, HalvesReproduceTheOriginal) {
  struct Case {
    std::string name;
    NurbsPatch patch;
    int direction;
    double value;
  };
  const std::vector<Case> cases = {{"quarter disc u", quarter_disc(1.0).patch, 0, 0.3},
                                   {"quarter disc v", quarter_disc(1.0).patch, 1, 0.5},
                                   {"sphere octant w", sphere_octant(1.0).patch, 2, 0.7},
                                   {"annulus u", quarter_annulus(1.0, 2.0).patch, 0, 0.25}};
  for (const auto& c : cases) {
    const auto [left, right] = split_patch(c.patch, c.direction, c.value);
    EXPECT_DOUBLE_EQ(left.knots(c.direction).last(), c.value) << c.name;
    EXPECT_DOUBLE_EQ(right.knots(c.direction).first(), c.value) << c.name;
    const int dim = c.patch.param_dim();
    for (int s = 0; s <= 10; ++s) {
      Eigen::VectorXd xi(dim);
      for (int k = 0; k < dim; ++k) xi[k] = (s * (k + 3) % 11) / 10.0;  // a scatter over the cube
      const Eigen::VectorXd x = c.patch.point(xi);
      const NurbsPatch& half = xi[c.direction] <= c.value ? left : right;
      EXPECT_LE((half.point(xi) - x).norm(), kSplitTolerance) << c.name << " at sample " << s;
    }
    // Both halves meet the cut at the same points.
    for (int s = 0; s <= 4; ++s) {
      Eigen::VectorXd xi = Eigen::VectorXd::Constant(dim, s / 4.0);
      xi[c.direction] = c.value;
      EXPECT_LE((left.point(xi) - right.point(xi)).norm(), kSplitTolerance) << c.name;
    }
  }
}

TEST(SplitPatch, AtAnExistingKnotAndOutsideTheRange) {
  const NurbsPatch p = normalised(split_patch(quarter_disc(1.0).patch, 0, 0.5).first);
  EXPECT_DOUBLE_EQ(p.knots(0).last(), 1.0);
  // 0.5 already a knot (multiplicity 1): the halves are those of the plain patch.
  const NurbsPatch disc = quarter_disc(1.0).patch;
  const NurbsPatch refined = insert_knots(disc, 0, {0.25, 0.5}).patch;
  const auto [r0, r1] = split_patch(refined, 0, 0.5);
  const auto [d0, d1] = split_patch(disc, 0, 0.5);
  EXPECT_EQ(r0.num_basis(0), 4);  // knots 0 0 0 0.25 0.5 0.5 0.5
  EXPECT_EQ(r1.num_basis(0), 3);
  expect_same_patch(r1, d1, kSplitTolerance, "right half");
  // A half keeps its range: splitting it again inside that range works.
  const auto [a1, a2] = split_patch(d0, 1, 0.25);
  EXPECT_EQ(a1.num_basis(1), 3);
  EXPECT_THROW(split_patch(p, 0, 1.0), SplineError);
  EXPECT_THROW(split_patch(p, 0, -0.1), SplineError);
  EXPECT_THROW(split_patch(p, 2, 0.5), SplineError);
}

// ---------------------------------------------------------------- round trips

TEST(GismoXml, EveryShapeRoundTrips) {
  const fs::path dir = temp_dir("shapes");
  const std::map<std::string, NurbsPatch> shapes = {{"quarter_disc", quarter_disc(1.0).patch},
                                                    {"sphere_octant", sphere_octant(1.0).patch},
                                                    {"quarter_annulus", quarter_annulus(1.0, 2.0).patch},
                                                    {"rectangle", rectangle(2.0, 0.5).patch},
                                                    {"box", box(1.0, 2.0, 3.0).patch}};
  for (const auto& [name, patch] : shapes) {
    const std::string path = (dir / (name + ".xml")).string();
    const MultiPatch body = single_patch_body(patch);
    write_gismo_xml(body, path);
    expect_same_body(read_gismo_xml(path), body, kRoundTrip, name);
  }
  fs::remove_all(dir);
}

TEST(GismoXml, MultiPatchBodiesRoundTripWithGismoInterfaceFlags) {
  const fs::path dir = temp_dir("bodies");
  for (const auto& [name, body] : make_bodies()) {
    const std::string path = (dir / fs::path(name).filename()).string();
    write_gismo_xml(body, path);
    expect_same_body(read_gismo_xml(path), body, kRoundTrip, name);
  }
  // The interface line of the two-patch disc: east of 0 on west of 1, same
  // directions, same orientation (what G+Smo's computeTopology finds).
  const std::string path = (dir / "quarter_disc_two_patches.xml").string();
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("0 2 1 1 0 1 1 1"), std::string::npos) << text;
  fs::remove_all(dir);
}

TEST(GismoXml, FlippedInterfaceGetsItsOrientation) {
  // Patch 1 is the right half of the quarter disc with u reversed, so its
  // east side meets patch 0's east side: the normal directions oppose (flag
  // 0), v keeps its sense (flag 1).
  auto [left, right] = halves(quarter_disc(1.0).patch, 0);
  const int n0 = right.num_basis(0), n1 = right.num_basis(1);
  Eigen::MatrixXd P(right.num_control_points(), 2);
  Eigen::VectorXd w(right.num_control_points());
  for (int j = 0; j < n1; ++j)
    for (int i = 0; i < n0; ++i) {
      P.row(i + n0 * j) = right.points().row(n0 - 1 - i + n0 * j);
      w[i + n0 * j] = right.weights()[n0 - 1 - i + n0 * j];
    }
  MultiPatch body;
  body.patches = {left, NurbsPatch(right.all_knots(), P, w)};
  body.interfaces = {{side(0, 2), side(1, 2)}};
  const fs::path dir = temp_dir("flipped");
  const std::string path = (dir / "flipped.xml").string();
  write_gismo_xml(body, path);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("0 2 1 2 0 1 0 1"), std::string::npos) << text;
  const MultiPatch back = read_gismo_xml(path);
  EXPECT_EQ(back.boundary.size(), 6u);  // the sides not in the interface
  fs::remove_all(dir);
}

TEST(GismoXml, PermutedInterfaceIn3DGetsItsDirectionMap) {
  // Patch 1 is the block's right half with v and w swapped: patch 0's v (y)
  // runs along patch 1's w and its w (z) along patch 1's v.
  auto [left, right] = halves(box(2.0, 2.0, 1.0).patch, 0);
  const int n0 = right.num_basis(0), n1 = right.num_basis(1), n2 = right.num_basis(2);
  Eigen::MatrixXd P(right.num_control_points(), 3);
  for (int k = 0; k < n1; ++k)      // new w = old v
    for (int j = 0; j < n2; ++j)    // new v = old w
      for (int i = 0; i < n0; ++i) P.row(i + n0 * (j + n2 * k)) = right.points().row(right.index({i, k, j}));
  MultiPatch body;
  body.patches = {left, NurbsPatch({right.knots(0), right.knots(2), right.knots(1)}, P, right.weights())};
  body.interfaces = {{side(0, 2), side(1, 1)}};
  const fs::path dir = temp_dir("permuted");
  const std::string path = (dir / "permuted.xml").string();
  write_gismo_xml(body, path);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("0 2 1 1 0 2 1 1 1 1"), std::string::npos) << text;
  EXPECT_EQ(read_gismo_xml(path).interfaces.size(), 1u);
  fs::remove_all(dir);
}

TEST(GismoXml, WriterRejectsSidesThatDoNotMeet) {
  auto [left, right] = halves(quarter_disc(1.0).patch, 0);
  MultiPatch body;
  body.patches = {left, right};
  body.interfaces = {{side(0, 1), side(1, 2)}};  // west of the left half is not on east of the right half
  const fs::path dir = temp_dir("apart");
  const std::string path = (dir / "apart.xml").string();
  try {
    write_gismo_xml(body, path);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": interface 0: side 1 of patch 0 and side 2 of patch 1 do not meet"),
              std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_empty(dir)) << "nothing is written";
  fs::remove_all(dir);
}

// ---------------------------------------------------------------- a G+Smo-layout file

TEST(GismoXml, ReadsAFileInGismoLayout) {
  const MultiPatch body = read_gismo_xml(source("tests/data/gismo_two_patches.xml"));
  ASSERT_EQ(body.patches.size(), 2u);
  EXPECT_EQ(body.patches[0].degree(0), 1);
  EXPECT_EQ(body.patches[1].degree(0), 2);
  ASSERT_EQ(body.interfaces.size(), 1u);
  EXPECT_TRUE(body.interfaces[0].first == side(0, 2));
  EXPECT_TRUE(body.interfaces[0].second == side(1, 1));
  ASSERT_EQ(body.boundary.size(), 6u);
  EXPECT_TRUE(body.boundary[3] == side(1, 2));
  // Patch 1: x(u) is the rational quadratic with control abscissae 1, 1.5, 2
  // and weights 1, 2, 1; y = v.
  for (double u : {0.0, 0.25, 0.5, 0.9}) {
    const double b0 = (1 - u) * (1 - u), b1 = 2 * u * (1 - u), b2 = u * u;
    const double x = (b0 * 1 + b1 * 2 * 1.5 + b2 * 2) / (b0 + 2 * b1 + b2);
    Eigen::VectorXd xi(2);
    xi << u, 0.3;
    EXPECT_NEAR(body.patches[1].point(xi)[0], x, kSplitTolerance);
    EXPECT_NEAR(body.patches[1].point(xi)[1], 0.3, kSplitTolerance);
  }
  // The two patches meet along x = 1.
  Eigen::VectorXd a(2), b(2);
  a << 1.0, 0.6;
  b << 0.0, 0.6;
  EXPECT_LE((body.patches[0].point(a) - body.patches[1].point(b)).norm(), kSplitTolerance);
}

// ---------------------------------------------------------------- bad files

// A good two-patch file (the layout above) that each bad case changes in one place.
const char* kGood = R"(<?xml version="1.0"?>
<xml>
 <Geometry type="TensorBSpline2" id="0">
  <Basis type="TensorBSplineBasis2">
   <Basis type="BSplineBasis" index="0"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
   <Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
  </Basis>
  <coefs geoDim="2">0 0
1 0
0 1
1 1</coefs>
 </Geometry>
 <Geometry type="TensorNurbs2" id="1">
  <Basis type="TensorNurbsBasis2">
   <Basis type="TensorBSplineBasis2">
    <Basis type="BSplineBasis" index="0"><KnotVector degree="2">0 0 0 1 1 1</KnotVector></Basis>
    <Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
   </Basis>
   <weights>1 2 1 1 2 1</weights>
  </Basis>
  <coefs geoDim="2">1 0 1.5 0 2 0 1 1 1.5 1 2 1</coefs>
 </Geometry>
 <MultiPatch parDim="2" id="2">
  <patches type="id_range">0 1</patches>
  <interfaces>0 2 1 1 0 1 1 1</interfaces>
  <boundary>0 1 0 3 0 4 1 2 1 3 1 4</boundary>
 </MultiPatch>
</xml>
)";

struct BadFile {
  std::string name, from, to;     // the one change to kGood
  std::string line_marker;        // text on the line the message names
  std::vector<std::string> fragments;  // element and reason
};

void PrintTo(const BadFile& c, std::ostream* os) { *os << c.name; }

class GismoXmlBadFile : public ::testing::TestWithParam<BadFile> {};

TEST_P(GismoXmlBadFile, OneLineNamingFileElementAndReason) {
  const BadFile& c = GetParam();
  std::string text = kGood;
  const size_t at = text.find(c.from);
  ASSERT_NE(at, std::string::npos) << c.from;
  text.replace(at, c.from.size(), c.to);
  const fs::path dir = temp_dir("bad");
  const fs::path path = dir / (c.name + ".xml");
  write_text(path, text);
  int line = 0;
  {
    std::istringstream lines(text);
    std::string l;
    for (int n = 1; std::getline(lines, l); ++n)
      if (line == 0 && l.find(c.line_marker) != std::string::npos) line = n;
  }
  try {
    read_gismo_xml(path.string());
    ADD_FAILURE() << c.name << ": no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
    EXPECT_EQ(msg.rfind(path.string() + ":" + std::to_string(line) + ": ", 0), 0u) << "file and line " << line << ": " << msg;
    for (const auto& f : c.fragments) EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' in: " << msg;
  }
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(
    BadFiles, GismoXmlBadFile,
    ::testing::Values(
        BadFile{"malformed_xml", "</coefs>\n </Geometry>\n <Geometry", "</coef>\n </Geometry>\n <Geometry", "</coef>",
                {"malformed XML"}},
        BadFile{"unknown_geometry_type", "TensorNurbs2\" id=\"1\"", "THBSpline2\" id=\"1\"", "THBSpline2",
                {"<Geometry id=\"1\">", "unknown geometry type \"THBSpline2\""}},
        BadFile{"coefficient_count", "1.5 1 2 1</coefs>", "1.5 1 2</coefs>", "1.5 1 2</coefs>",
                {"<Geometry id=\"1\"> <coefs>", "11 numbers where 6 control points (the basis sizes 3 x 2)"}},
        BadFile{"knots_decrease", "0 0 0 1 1 1", "0 0 0.5 0.2 1 1", "0.5 0.2",
                {"<Geometry id=\"1\"> <KnotVector> of direction 0", "decrease"}},
        BadFile{"zero_weight", "<weights>1 2 1 1 2 1", "<weights>1 2 1 0 2 1", "<weights>",
                {"<Geometry id=\"1\"> <weights>", "weight 0 of control point 3 is not positive"}},
        BadFile{"negative_weight", "<weights>1 2 1 1 2 1", "<weights>1 -2 1 1 2 1", "<weights>",
                {"<weights>", "weight -2 of control point 1 is not positive"}},
        BadFile{"infinite_weight", "<weights>1 2 1 1 2 1", "<weights>1 2 inf 1 2 1", "<weights>",
                {"<weights>", "entry 2 is not finite"}},
        // (1e308 passed as positive and finite, and the patch then "folded")
        BadFile{"huge_weight", "<weights>1 2 1 1 2 1", "<weights>1 2 1 1 1e308 1", "<weights>",
                {"<weights>", "the weights range from 1 to 1e+308, more than 1e100 apart"}},
        BadFile{"huge_coordinate", "1.5 0 2 0", "1.5 0 2e200 0", "2e200",
                {"<coefs>", "control point 2 has a coordinate beyond 1e100 (2e+200)"}},
        BadFile{"weight_count", "<weights>1 2 1 1 2 1", "<weights>1 2 1 1 2", "<weights>",
                {"<weights>", "5 weights where the basis (sizes 3 x 2) has 6 functions"}},
        BadFile{"degree_does_not_fit", "degree=\"2\">0 0 0 1 1 1", "degree=\"3\">0 0 0 1 1 1", "degree=\"3\"",
                {"<KnotVector> of direction 0", "degree 3 needs at least 8 knots"}},
        BadFile{"interface_patch_missing", "<interfaces>0 2 1 1", "<interfaces>0 2 7 1", "<interfaces>",
                {"<MultiPatch> <interfaces>", "patch 7 does not exist"}},
        BadFile{"boundary_patch_missing", "<boundary>0 1 0 3", "<boundary>0 1 5 3", "<boundary>",
                {"<MultiPatch> <boundary>", "patch 5 does not exist"}},
        BadFile{"side_out_of_range", "<boundary>0 1 0 3", "<boundary>0 1 0 5", "<boundary>",
                {"<MultiPatch> <boundary>", "side 5 is not a side of a 2D patch (1..4)"}},
        BadFile{"interface_side_out_of_range", "<interfaces>0 2 1 1", "<interfaces>0 2 1 0", "<interfaces>",
                {"<MultiPatch> <interfaces>", "side 0 is not a side"}},
        BadFile{"interface_sides_apart", "<interfaces>0 2 1 1", "<interfaces>0 1 1 2", "<interfaces>",
                {"<MultiPatch> <interfaces>", "side 1 (west) of patch 0 and side 2 (east) of patch 1 do not meet"}},
        BadFile{"interface_integer_count", "0 2 1 1 0 1 1 1</interfaces>", "0 2 1 1 0 1 1</interfaces>", "<interfaces>",
                {"<MultiPatch> <interfaces>", "7 integers do not make whole interfaces of 8"}},
        BadFile{"old_form_flag", "0 2 1 1 0 1 1 1</interfaces>", "0 2 1 1 3</interfaces>", "<interfaces>",
                {"<MultiPatch> <interfaces>", "interface 0: orientation flag 3 is not 0 or 1"}},
        BadFile{"interface_direction_map", "0 2 1 1 0 1 1 1</interfaces>", "0 2 1 1 1 0 1 1</interfaces>", "<interfaces>",
                {"<MultiPatch> <interfaces>", "sends the normal direction 0"}},
        BadFile{"side_listed_twice", "<boundary>0 1 0 3", "<boundary>0 2 0 3", "<boundary>",
                {"<MultiPatch> <boundary>", "side 2 (east) of patch 0 is already listed"}},
        BadFile{"par_dim_mismatch", "parDim=\"2\"", "parDim=\"3\"", "TensorBSpline2",
                {"<Geometry id=\"0\">", "a 2D patch in a <MultiPatch parDim=\"3\">"}},
        // (geoDim 3 on a 2D patch is read in the plane when every z is 0:
        // test_gismo_planar.cpp; here 4 is no space igac reads.)
        BadFile{"geo_dim_mismatch", "<coefs geoDim=\"2\">0 0", "<coefs geoDim=\"4\">0 0", "geoDim=\"4\"",
                {"<Geometry id=\"0\"> <coefs>", "geoDim 4 differs from the parametric dimension 2"}},
        BadFile{"missing_patch_id", "<patches type=\"id_range\">0 1", "<patches type=\"id_range\">0 2", "<patches",
                {"<MultiPatch> <patches>", "no <Geometry> with id 2"}},
        BadFile{"not_a_number", "1.5 0 2 0", "1.5 0 two 0", "two",
                {"<Geometry id=\"1\"> <coefs>", "\"two\" (entry 4) is not a number"}}),
    [](const ::testing::TestParamInfo<BadFile>& i) { return i.param.name; });

// Older G+Smo files write an interface as patch side patch side and dim - 1
// orientation flags (five numbers in 2D): the same interface is read.
TEST(GismoXml, OlderFiveNumberInterfaceForm) {
  std::ifstream in(source("tests/data/quarter_disc_two_patches.xml"));
  std::string xml{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::string current = "0 2 1 1 0 1 1 1\n</interfaces>";
  ASSERT_NE(xml.find(current), std::string::npos);
  xml.replace(xml.find(current), current.size(), "0 2 1 1 1\n</interfaces>");
  const fs::path dir = temp_dir("old_form");
  write_text(dir / "old.xml", xml);
  const MultiPatch older = read_gismo_xml((dir / "old.xml").string());
  const MultiPatch now = read_gismo_xml(source("tests/data/quarter_disc_two_patches.xml"));
  ASSERT_EQ(older.interfaces.size(), 1u);
  EXPECT_EQ(older.interfaces[0].first, now.interfaces[0].first);
  EXPECT_EQ(older.interfaces[0].second, now.interfaces[0].second);
  EXPECT_EQ(older.boundary.size(), now.boundary.size());
}

TEST(GismoXml, MissingFileAndWrongRoot) {
  EXPECT_THROW(read_gismo_xml("/nonexistent/igac/body.xml"), InputError);
  const fs::path dir = temp_dir("root");
  write_text(dir / "root.xml", "<?xml version=\"1.0\"?>\n<gismo/>\n");
  try {
    read_gismo_xml((dir / "root.xml").string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("root.xml:2: <gismo>: the root element"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

// ---------------------------------------------------------------- test data

TEST(GismoXmlData, TwoSectorsAreTheQuarterDisc) {
  const MultiPatch body = quarter_disc_two_sectors();
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k <= 8; ++k) {
      Eigen::VectorXd xi(2);
      xi << k / 8.0, 0.0;  // the arc: on the unit circle, x >= 0, y <= 0
      const Eigen::VectorXd x = body.patches[i].point(xi);
      EXPECT_NEAR(x.norm(), 1.0, kRoundTrip * 10) << "patch " << i;
      EXPECT_GE(x[0], -kRoundTrip);
      EXPECT_LE(x[1], kRoundTrip);
    }
  // The arc halves meet at M, at 45 degrees, and the contact point is patch 0's (0, 0).
  Eigen::VectorXd a(2), b(2);
  a << 1.0, 0.0;
  b << 0.0, 0.0;
  EXPECT_LE((body.patches[0].point(a) - body.patches[1].point(b)).norm(), kSplitTolerance);
  EXPECT_LE((body.patches[0].point(b) - Eigen::Vector2d(0, -1)).norm(), kSplitTolerance);
}

TEST(GismoXmlData, CheckedInFilesAreTheGeneratedBodies) {
  const bool regenerate = std::getenv("IGAC_REGENERATE_XML") != nullptr;
  for (const auto& [name, body] : make_bodies()) {
    if (regenerate) write_gismo_xml(body, source(name));
    expect_same_body(read_gismo_xml(source(name)), body, kRoundTrip, name);
    // Every patch is a valid map: det J > 0 at interior sample points.
    for (size_t i = 0; i < body.patches.size(); ++i) {
      const NurbsPatch& p = body.patches[i];
      for (int k = 0; k < 125; ++k) {
        Eigen::VectorXd xi(p.param_dim());
        for (int d = 0; d < p.param_dim(); ++d) xi[d] = 0.1 + 0.2 * ((k / (d == 0 ? 1 : d == 1 ? 5 : 25)) % 5);
        EXPECT_GT(p.jacobian(xi).determinant(), 0) << name << " patch " << i;
      }
    }
    // Conforming interfaces: the two sides carry the same control points.
    for (const auto& pi : body.interfaces) {
      const NurbsPatch fa = body.patches[pi.first.patch].face_patch(pi.first.face);
      const NurbsPatch fb = body.patches[pi.second.patch].face_patch(pi.second.face);
      EXPECT_LE(relative_difference(fa.points(), fb.points()), kSplitTolerance) << name;
      EXPECT_LE(relative_difference(fa.weights(), fb.weights()), kSplitTolerance) << name;
    }
  }
}

// ---------------------------------------------------------------- igac geometry

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

Outcome run_igac(const std::string& args, const fs::path& dir) {
  const fs::path err = dir / "stderr.txt";
  const std::string cmd = std::string("'") + IGAC_BINARY + "' " + args + " 2>'" + err.string() + "'";
  Outcome o;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return o;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) o.out.append(buf.data(), n);
  const int status = pclose(pipe);
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  o.err.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  fs::remove(err);
  return o;
}

TEST(GismoXmlCli, WritesTheCaseBodyWhichReadsBackEqual) {
  const fs::path dir = temp_dir("cli");
  const std::map<std::string, NurbsPatch> cases = {{"cases/hertz2d.toml", quarter_disc(1.0).patch},
                                                   {"cases/hertz3d.toml", sphere_octant(1.0).patch},
                                                   {"cases/lame_cylinder.toml", quarter_annulus(1.0, 2.0).patch}};
  for (const auto& [c, patch] : cases) {
    const fs::path out = dir / "body.xml";
    const Outcome o = run_igac("geometry '" + source(c) + "' --out '" + out.string() + "'", dir);
    ASSERT_EQ(o.exit_code, 0) << c << ": " << o.err;
    expect_same_body(read_gismo_xml(out.string()), single_patch_body(patch), kRoundTrip, c);
    fs::remove(out);
  }
  fs::remove_all(dir);
}

TEST(GismoXmlCli, BadCaseExitsTwoWithOneLineAndWritesNothing) {
  const fs::path dir = temp_dir("cli_bad");
  const fs::path out = dir / "body.xml";
  const Outcome o = run_igac("geometry '" + source("tests/data/bad_unknown_shape.toml") + "' --out '" + out.string() + "'", dir);
  EXPECT_EQ(o.exit_code, kBadInputExit);
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
  EXPECT_EQ(o.err.rfind("igac: error: " + source("tests/data/bad_unknown_shape.toml"), 0), 0u) << o.err;
  EXPECT_FALSE(fs::exists(out));
  // An output folder that does not exist: the same, nothing written.
  const Outcome o2 = run_igac("geometry '" + source("cases/hertz2d.toml") + "' --out '" + (dir / "no/such/dir/b.xml").string() + "'", dir);
  EXPECT_EQ(o2.exit_code, kBadInputExit);
  EXPECT_EQ(std::count(o2.err.begin(), o2.err.end(), '\n'), 1) << o2.err;
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

}  // namespace
