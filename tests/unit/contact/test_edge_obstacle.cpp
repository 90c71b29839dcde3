// SPDX-License-Identifier: BSD-3-Clause
// The rigid edge (contact/obstacles/edge.hpp): two faces meeting at a
// rounded corner.
//  - the gap's gradient is the normal and the normal's derivative matches
//    central differences at points nearest each face, the rounded tip and
//    inside, in 2D and 3D, for a right, an acute and an obtuse edge;
//  - the normal is continuous where the regions meet, and a point nearest
//    a face has that face's plane gap exactly;
//  - the reach past the edge is the distance beyond the first face, over
//    the second (0 elsewhere; none for an obstacle without an edge);
//  - a block pushed against a wall that ends below its top reports how far
//    its face passes the edge (between the top corner's displacement and
//    its control points' hull), 0 with the edge above it;
//  - a block pressed by the edge's rounded tip gives the same contact as
//    the rigid circle of that radius to round-off, in small and large
//    deformation (the contact stays on the tip).
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <string>

#include "contact/obstacle.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/case_texts.hpp"

namespace igac {
namespace {

Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd out(Eigen::Index(v.size()));
  Eigen::Index i = 0;
  for (double x : v) out[i++] = x;
  return out;
}

void expect_derivatives_match(const RigidEdge& edge, const Eigen::VectorXd& x) {
  const ObstacleProbe p = edge.probe(x, true);
  EXPECT_NEAR(p.normal.norm(), 1.0, 1e-14);
  const double h = 1e-6;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(x.size());
    e[j] = h;
    const ObstacleProbe pp = edge.probe(x + e), pm = edge.probe(x - e);
    EXPECT_NEAR((pp.gap - pm.gap) / (2 * h), p.normal[j], 1e-8) << "dg/dx = n at " << x.transpose();
    EXPECT_LE(((pp.normal - pm.normal) / (2 * h) - p.normal_derivative.col(j)).norm(), 1e-7)
        << "dn/dx column " << j << " at " << x.transpose();
  }
}

TEST(ObstacleEdge, GapAndNormalDerivativesMatchFiniteDifferences2D) {
  // A gland's wall x = 1 (normal -x) ending at the land y = 2 (normal +y),
  // rounded 0.2; then an acute and an obtuse edge at the origin.
  const RigidEdge right(vec({1.0, 2.0}), vec({-1.0, 0.0}), vec({0.0, 1.0}), 0.2);
  for (const auto& x : {vec({0.5, 1.0}), vec({1.5, 2.4}), vec({0.6, 2.3}), vec({1.1, 1.95}), vec({0.7, 1.5})})
    expect_derivatives_match(right, x);
  const RigidEdge acute(vec({0.0, 0.0}), vec({-1.0, 0.3}), vec({1.0, 0.3}), 0.1);
  const RigidEdge obtuse(vec({0.0, 0.0}), vec({-0.3, 1.0}), vec({0.3, 1.0}), 0.1);
  for (const auto& x : {vec({-0.5, 0.2}), vec({0.5, 0.3}), vec({0.01, 0.5}), vec({0.02, -0.3})}) {
    expect_derivatives_match(acute, x);
    expect_derivatives_match(obtuse, x);
  }
}

TEST(ObstacleEdge, GapAndNormalDerivativesMatchFiniteDifferences3D) {
  const RigidEdge edge(vec({0.0, 0.0, 0.0}), vec({-1.0, 0.0, 0.2}), vec({0.1, 0.0, 1.0}), 0.3);
  for (const auto& x : {vec({-0.8, 0.5, -0.2}), vec({0.3, -1.0, 0.9}), vec({-0.4, 2.0, 0.5}), vec({-0.5, 0.0, -0.6})})
    expect_derivatives_match(edge, x);
}

TEST(ObstacleEdge, ANormalIsContinuousAndAFacesGapIsItsPlanes) {
  const double r = 0.2;
  const RigidEdge edge(vec({1.0, 2.0}), vec({-1.0, 0.0}), vec({0.0, 1.0}), r);
  // The wall's region ends at y = 2 - r (level with the tip's centre).
  for (double y : {2 - r - 1e-9, 2 - r + 1e-9}) {
    const ObstacleProbe p = edge.probe(vec({0.7, y}));
    EXPECT_LE((p.normal - vec({-1.0, 0.0})).norm(), 1e-8) << y;
    EXPECT_NEAR(p.gap, 0.3, 1e-8) << y;
  }
  // Nearest the wall: the plane x = 1's gap, nearest the land: y = 2's.
  EXPECT_NEAR(edge.probe(vec({0.25, 0.5})).gap, 0.75, 1e-15);
  EXPECT_NEAR(edge.probe(vec({3.0, 2.125})).gap, 0.125, 1e-15);
  // Past the tip's centre diagonally: the distance from the arc.
  const Eigen::VectorXd centre = vec({1.0 + r, 2.0 - r});
  const Eigen::VectorXd x = centre + 0.5 * vec({-1.0, 1.0}).normalized();
  EXPECT_NEAR(edge.probe(x).gap, 0.5 - r, 1e-15);
}

TEST(ObstacleEdge, ReachPastTheEdgeIsBeyondTheFirstFaceOverTheSecond) {
  const RigidEdge edge(vec({1.0, 2.0}), vec({-1.0, 0.0}), vec({0.0, 1.0}), 0.2);
  EXPECT_EQ(edge.reach_past_edge(vec({1.3, 1.9})), 0.0);  // below the land: on the rigid body's side
  EXPECT_EQ(edge.reach_past_edge(vec({0.9, 2.1})), 0.0);  // above the land but not past the wall
  EXPECT_FALSE(RigidPlane(vec({0.0, 0.0}), vec({0.0, 1.0})).reach_past_edge(vec({1.0, 1.0}))) << "a plane has no edge";
  ASSERT_TRUE(edge.reach_past_edge(vec({1.25, 2.05})));
  EXPECT_NEAR(*edge.reach_past_edge(vec({1.25, 2.05})), 0.25, 1e-15);
  const TranslatedObstacle moved(edge, vec({0.0, 1.0}));
  ASSERT_TRUE(moved.reach_past_edge(vec({1.25, 3.05})));
  EXPECT_NEAR(*moved.reach_past_edge(vec({1.25, 3.05})), 0.25, 1e-15);
}

// A 2 x 1 block held at its bottom, pressed 0.01 deep by `obstacle`.
ContactResult pressed_block(const std::string& obstacle, const std::string& model) {
  const std::string text = igac_test::rectangle_case(2.0, 1.0, 32, 8, model) + igac_test::rollers() + R"(
[contact]
face = "top"
[contact.obstacle]
)" + obstacle + "\nmotion = [0.0, -0.01]\n";
  RunResult r = solve_model(build_model(read_case_text(text, std::string(IGAC_SOURCE_DIR) + "/cases/edge.toml")),
                            quiet_run());
  EXPECT_FALSE(r.contacts.empty());
  return r.contacts.empty() ? ContactResult{} : std::move(r.contacts.front());
}

TEST(ObstacleEdge, ItsRoundedTipPressesAsTheCircleOfItsRadius) {
  // The circle of radius 1 about (1, 2) touches the block's top at x = 1;
  // the edge pointing down (faces at 45 degrees) has that circle as its tip.
  const std::string circle = "type = \"sphere\"\ncentre = [1.0, 2.0]\nradius = 1.0";
  const std::string edge = fmt::format(
      "type = \"edge\"\npoint = [1.0, {:.17g}]\nnormal = [-1.0, -1.0]\nsecond_normal = [1.0, -1.0]\nradius = 1.0",
      2.0 - std::sqrt(2.0));
  for (const char* model : {"linear_elastic", "neo_hookean"}) {
    const ContactResult a = pressed_block(circle, model), b = pressed_block(edge, model);
    EXPECT_GT(a.report.total_force, 0) << model;
    EXPECT_NEAR(b.report.total_force, a.report.total_force, 1e-9 * a.report.total_force) << model;
    EXPECT_NEAR(b.report.max_pressure, a.report.max_pressure, 1e-9 * a.report.max_pressure) << model;
    EXPECT_EQ(b.report.active, a.report.active) << model;
  }
}

// A unit block on a floor (y held), pushed by a pressure on its left face
// against a wall x = 1 that ends in a rounded edge at height `land`.
RunResult block_against_a_wall(double land) {
  const std::string text = igac_test::rectangle_case(1.0, 1.0, 8, 8) + fmt::format(R"(
[[dirichlet]]
faces = ["bottom"]
component = "y"
[[pressure]]
faces = ["left"]
value = 0.05
[contact]
face = "right"
[contact.obstacle]
type = "edge"
point = [1.0, {}]
normal = [-1.0, 0.0]
second_normal = [0.0, 1.0]
radius = 0.05
)", land);
  return solve_model(build_model(read_case_text(text, std::string(IGAC_SOURCE_DIR) + "/cases/edge.toml")),
                     quiet_run());
}

TEST(ObstacleEdge, TheExtrusionIsHowFarTheFacePassesTheEdge) {
  // Above the land the right face bulges out past x = 1: the report lies
  // between the top corner's displacement (a point it samples) and the
  // largest of the face's control points' (the face lies in their hull).
  const RunResult r = block_against_a_wall(0.5);
  ASSERT_TRUE(r.status.is_converged()) << r.status.text();
  ASSERT_EQ(r.reactions.size(), 1u);
  ASSERT_TRUE(r.reactions.front().extrusion);
  const double extrusion = *r.reactions.front().extrusion;
  const int nx = 8 + 2, corner = nx * nx - 1;  // the top right control point
  double hull = 0;
  for (int j = 0; j < nx; ++j) hull = std::max(hull, r.u(j * nx + nx - 1, 0));
  std::printf("  extrusion %.6g: top corner %.6g, hull %.6g\n", extrusion, r.u(corner, 0), hull);
  EXPECT_GT(r.u(corner, 0), 1e-3);
  EXPECT_GE(extrusion, r.u(corner, 0) - 1e-15);
  EXPECT_LE(extrusion, hull + 1e-15);
  // With the land above the block nothing passes the edge.
  const RunResult below = block_against_a_wall(1.2);
  ASSERT_TRUE(below.reactions.front().extrusion);
  EXPECT_EQ(*below.reactions.front().extrusion, 0.0);
}

}  // namespace
}  // namespace igac
