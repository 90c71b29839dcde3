// SPDX-License-Identifier: BSD-3-Clause
// Sides of a geometry file that coincide are joined even when the file does
// not say so (engine/geometry/topology.hpp): the seam of a closed ring was
// solved as a slit (a circumferential displacement as large as the radial
// one where the exact one is 0), and a <MultiPatch> without <interfaces>
// ended in "stiffness matrix is not positive definite".  Sides the file's
// <boundary> lists stay apart with a warning, as do sides sharing only
// corners; collapsed sides join nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "engine/geometry/topology.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

namespace fs = std::filesystem;

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / "igac_coincident_sides";
  fs::create_directories(dir);
  return dir;
}

// A full ring a <= r <= b as ONE patch: u runs once around (the 4-arc NURBS
// circle, first and last control points equal: the seam), v outward.
// `topology` is put after the <Geometry> (a <MultiPatch>, or nothing).
std::string ring_file(const std::string& name, double a, double b, const std::string& topology = "") {
  const double h = std::sqrt(0.5);
  const double cx[] = {1, 1, 0, -1, -1, -1, 0, 1, 1}, cy[] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
  std::ostringstream xml;
  xml << "<xml>\n<Geometry type=\"TensorNurbs2\" id=\"0\">\n<Basis type=\"TensorNurbsBasis2\">\n"
         "<Basis type=\"TensorBSplineBasis2\">\n"
         "<Basis type=\"BSplineBasis\" index=\"0\"><KnotVector degree=\"2\">0 0 0 1 1 2 2 3 3 4 4 4</KnotVector></Basis>\n"
         "<Basis type=\"BSplineBasis\" index=\"1\"><KnotVector degree=\"1\">0 0 1 1</KnotVector></Basis>\n"
         "</Basis>\n<weights>";
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 9; ++i) xml << (i % 2 ? h : 1.0) << " ";
  xml.precision(17);
  xml << "</weights>\n</Basis>\n<coefs geoDim=\"2\">\n";
  for (double r : {a, b})
    for (int i = 0; i < 9; ++i) xml << r * cx[i] << " " << r * cy[i] << "\n";
  xml << "</coefs>\n</Geometry>\n" << topology << "</xml>\n";
  const fs::path path = scratch() / name;
  std::ofstream(path) << xml.str();
  return path.string();
}

Model model_of(const std::string& case_name, const std::string& body) {
  const fs::path toml = scratch() / (case_name + ".toml");
  std::ofstream(toml) << body;
  return build_model(read_case(toml.string()));
}

// Plane strain ring clamped at r = b, inner pressure p: u_r = A r + B / r
// with u_r(b) = 0 and sigma_r(a) = -p.
double clamped_ring_radial(double r, double a, double b, double p, double E, double nu) {
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const double A = -p / (2 * (lambda + mu) + 2 * mu * b * b / (a * a));
  return A * r - A * b * b / r;
}

TEST(CoincidentSides, ClosedRingIsJoinedAlongItsSeamAndStaysAxisymmetric) {
  const double a = 1, b = 2, p = 0.01, E = 1, nu = 0.3;
  const std::string file = ring_file("ring.xml", a, b);
  const Model m = model_of("ring", "[geometry]\nfile = \"" + file +
                                       "\"\n[mesh]\ndegree = 3\nelements = [32, 8]\n"
                                       "[material]\nE = 1.0\nnu = 0.3\n"
                                       "[[dirichlet]]\nfaces = [\"0:north\"]\ncomponent = \"x\"\n"
                                       "[[dirichlet]]\nfaces = [\"0:north\"]\ncomponent = \"y\"\n"
                                       "[[pressure]]\nfaces = [\"0:south\"]\nvalue = 0.01\n");
  ASSERT_EQ(m.joined_sides.size(), 1u);
  EXPECT_EQ(side_label(m.joined_sides[0].first), "0:west");
  EXPECT_EQ(side_label(m.joined_sides[0].second), "0:east");
  const RunResult r = solve_model(m);
  ASSERT_EQ(r.status, "converged");
  // Around the inner circle: radial displacement as Lame's, no
  // circumferential one.  (Cut open along the seam, the ring opened: the
  // circumferential displacement was of the radial one's size.)
  const NurbsPatch& patch = m.body.patch(0);
  const Eigen::MatrixXd u = m.body.patch_field(0, r.u);
  const double exact = clamped_ring_radial(a, a, b, p, E, nu);
  double worst_radial = 0, worst_tangential = 0;
  for (int k = 0; k <= 40; ++k) {
    const Eigen::Vector2d xi(k / 40.0, 0.0);
    const Eigen::VectorXd X = patch.point(xi), d = patch.field(u, xi);
    const Eigen::Vector2d er = X.normalized(), et(-er[1], er[0]);
    worst_radial = std::max(worst_radial, std::abs(d.dot(er) - exact));
    worst_tangential = std::max(worst_tangential, std::abs(d.dot(et)));
  }
  EXPECT_GT(exact, 0);
  EXPECT_LT(worst_radial, 1e-4 * exact);
  EXPECT_LT(worst_tangential, 1e-4 * exact);
}

TEST(CoincidentSides, SeamTheFileListsAsBoundaryStaysASlitWithAWarning) {
  const std::string file = ring_file("ring_slit.xml", 1, 2,
                                     "<MultiPatch parDim=\"2\" id=\"1\"><patches type=\"id_range\">0 0</patches>"
                                     "<boundary>0 1 0 2 0 3 0 4</boundary></MultiPatch>\n");
  const Model m = model_of("ring_slit", "[geometry]\nfile = \"" + file +
                                            "\"\n[mesh]\ndegree = 2\nelements = [8, 2]\n"
                                            "[material]\nE = 1.0\nnu = 0.3\n"
                                            "[[dirichlet]]\nfaces = [\"0:north\"]\ncomponent = \"x\"\n");
  EXPECT_TRUE(m.joined_sides.empty());
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("sides 0:west and 0:east coincide, but the file's <boundary> lists them"),
            std::string::npos)
      << m.warnings[0];
  EXPECT_TRUE(m.body.interfaces().empty());
}

// The two-patch quarter disc of hertz2d_two_patches with its topology
// removed, or written as G+Smo's volumes/cube.xml is (several <Geometry>,
// one id, no <MultiPatch>): the same body as with the file's <interfaces>.
TEST(CoincidentSides, PatchesWithoutInterfacesAreJoinedAsTheFileWouldJoinThem) {
  const std::string source = IGAC_SOURCE_DIR "/tests/data/quarter_disc_two_patches.xml";
  std::ifstream in(source);
  const std::string xml{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::string no_topology = std::regex_replace(xml, std::regex("<interfaces>[^<]*</interfaces>|<boundary>[^<]*</boundary>"), "");
  std::string no_multipatch = std::regex_replace(xml, std::regex("<MultiPatch[\\s\\S]*?</MultiPatch>"), "");
  no_multipatch = std::regex_replace(no_multipatch, std::regex("id=\"1\""), "id=\"0\"");
  std::ofstream(scratch() / "no_topology.xml") << no_topology;
  std::ofstream(scratch() / "no_multipatch.xml") << no_multipatch;
  auto run = [&](const std::string& file) {
    return model_of("two_sectors", "[geometry]\nfile = \"" + file +
                                       "\"\n[mesh]\ndegree = 2\nelements = [6, 4]\n[material]\nE = 1.0\nnu = 0.3\n"
                                       "[[dirichlet]]\nfaces = [\"0:west\"]\ncomponent = \"x\"\n"
                                       "[[dirichlet]]\nfaces = [\"1:north\"]\ncomponent = \"y\"\n"
                                       "[[pressure]]\nfaces = [\"0:south\", \"1:south\"]\nvalue = 0.01\n");
  };
  const Model given = run(source);
  const RunResult reference = solve_model(given);
  ASSERT_EQ(reference.status, "converged");
  EXPECT_TRUE(given.joined_sides.empty());
  for (const char* file : {"no_topology.xml", "no_multipatch.xml"}) {
    SCOPED_TRACE(file);
    const Model found = run((scratch() / file).string());
    ASSERT_EQ(found.joined_sides.size(), 1u);
    EXPECT_EQ(side_label(found.joined_sides[0].first), "0:east");
    EXPECT_EQ(side_label(found.joined_sides[0].second), "1:west");
    EXPECT_EQ(found.body.num_control_points(), given.body.num_control_points());
    const RunResult r = solve_model(found);
    ASSERT_EQ(r.status, "converged");
    EXPECT_LE((r.u - reference.u).norm(), 1e-12 * reference.u.norm());
  }
}

// Two unit squares side by side, the second's left side bulging out by
// `bulge` at its middle; triangles (a side collapsed to a point) for the
// degenerate case.
NurbsPatch quad(const std::vector<Eigen::Vector2d>& corners_and_mid_left) {
  // degree 1 in u (left -> right), 2 in v; control points row by row (u fastest)
  const auto& c = corners_and_mid_left;  // lower-left, lower-right, mid-left, mid-right, upper-left, upper-right
  Eigen::MatrixXd P(6, 2);
  for (int i = 0; i < 6; ++i) P.row(i) = c[i].transpose();
  return NurbsPatch({KnotVector(1, {0, 0, 1, 1}), KnotVector(2, {0, 0, 0, 1, 1, 1})}, P, Eigen::VectorXd::Ones(6));
}

TEST(CoincidentSides, CornersAloneAndCollapsedSidesJoinNothing) {
  const NurbsPatch left = quad({{0, 0}, {1, 0}, {0, 0.5}, {1, 0.5}, {0, 1}, {1, 1}});
  const NurbsPatch bulging = quad({{1, 0}, {2, 0}, {1.2, 0.5}, {2, 0.5}, {1, 1}, {2, 1}});
  const NurbsPatch straight = quad({{1, 0}, {2, 0}, {1, 0.5}, {2, 0.5}, {1, 1}, {2, 1}});
  std::vector<PatchSide> all;
  for (int k = 0; k < 2; ++k)
    for (int s = 1; s <= 4; ++s) all.push_back(PatchSide{k, face_of_gismo_side(s)});
  const CoincidentSides joined = find_coincident_sides({left, straight}, all);
  ASSERT_EQ(joined.coincide.size(), 1u);
  EXPECT_EQ(side_label(joined.coincide[0].first), "0:east");
  EXPECT_EQ(side_label(joined.coincide[0].second), "1:west");
  EXPECT_TRUE(joined.corners_only.empty());
  const CoincidentSides bulge = find_coincident_sides({left, bulging}, all);
  EXPECT_TRUE(bulge.coincide.empty());
  ASSERT_EQ(bulge.corners_only.size(), 1u);
  EXPECT_EQ(side_label(bulge.corners_only[0].first), "0:east");
  // Two triangles whose south sides collapse to the same point: the points
  // coincide, but a point has no length to share.
  const NurbsPatch t0 = quad({{0, 0}, {0, 0}, {-1, 0.5}, {1, 0.5}, {-1, 1}, {1, 1}});
  const NurbsPatch t1 = quad({{0, 0}, {0, 0}, {-1, -0.5}, {1, -0.5}, {-1, -1}, {1, -1}});
  // (t0's and t1's "south" is v = 0, u from lower-left to lower-right: the point (0, 0))
  const CoincidentSides collapsed = find_coincident_sides({t0, t1}, all);
  for (const PatchInterface& i : collapsed.coincide)
    EXPECT_FALSE(i.first.face == face_of_gismo_side(3) && i.second.face == face_of_gismo_side(3));
}

}  // namespace
}  // namespace igac
