// SPDX-License-Identifier: BSD-3-Clause
// The master surface of a two-body contact (contact/master_surface.hpp):
// closest-point projection onto exact NURBS arcs and spheres against the
// closed form, the tree search against trying every element, the number of
// elements a query visits, and a moved surface.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "contact/master_surface.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/spline/refinement.hpp"

namespace igac {
namespace {

// Newton converges to round-off of the coordinates (size ~1).
constexpr double kProjection = 1e-12;

Body refined(const Geometry& g, int degree, int parts) { return Body(subdivide(elevate_to(g.patch, degree), parts)); }

TEST(MasterSurface, ProjectsOntoACircularArcAsTheClosedForm) {
  const Geometry g = quarter_annulus(1.0, 2.0);
  const Body body = refined(g, 2, 8);
  const MasterSurface outer(body, {g.faces.at("outer")[0]});
  for (double theta : {0.05, 0.4, 0.785, 1.2, 1.52})
    for (double rho : {1.7, 1.99, 2.0, 2.3, 5.0}) {
      const Eigen::Vector2d x(rho * std::cos(theta), rho * std::sin(theta));
      const auto mp = outer.project(x);
      ASSERT_TRUE(mp);
      EXPECT_NEAR((mp->x - 2.0 * x.normalized()).norm(), 0, kProjection) << theta << " " << rho;
      EXPECT_NEAR(mp->gap, rho - 2.0, kProjection);
      EXPECT_NEAR((mp->normal - x.normalized()).norm(), 0, kProjection);  // outward: away from the centre
    }
  // The inner arc's outward normal points to the centre: a point at r = 0.8
  // is outside the body by 0.2.
  const MasterSurface inner(body, {g.faces.at("inner")[0]});
  const auto mp = inner.project(Eigen::Vector2d(0.8 * std::cos(0.3), 0.8 * std::sin(0.3)));
  ASSERT_TRUE(mp);
  EXPECT_NEAR(mp->gap, 0.2, kProjection);
}

TEST(MasterSurface, ProjectsOntoASphereAsTheClosedForm) {
  const Geometry g = sphere_octant(1.0);
  const Body body = refined(g, 2, 6);
  const MasterSurface sphere(body, {g.faces.at("curved")[0]});
  for (const Eigen::Vector3d dir : {Eigen::Vector3d(1, 1, -1), Eigen::Vector3d(0.2, 0.5, -0.9), Eigen::Vector3d(0.8, 0.1, -0.3)})
    for (double rho : {0.9, 1.0, 1.25}) {
      const Eigen::Vector3d x = rho * dir.normalized();
      const auto mp = sphere.project(x);
      ASSERT_TRUE(mp);
      EXPECT_NEAR((mp->x - dir.normalized()).norm(), 0, kProjection);
      EXPECT_NEAR(std::abs(mp->gap), std::abs(rho - 1.0), kProjection);
    }
}

TEST(MasterSurface, TreeFindsWhatEveryElementFindsVisitingFew) {
  // The average number of elements a query near the surface runs Newton on,
  // at 256, 1024 and 4096 master elements: bounded, not growing with them.
  const Geometry g = sphere_octant(1.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.05, 1.0), radius(0.97, 1.03);
  std::vector<double> per_query;
  for (int parts : {16, 32, 64}) {
    // Refined along the curved face only (directions u and w).
    NurbsPatch patch = elevate_to(g.patch, 3);
    for (int d : {0, 2}) patch = refine_to(patch, d, KnotVector::uniform(3, parts));
    const Body body(patch);
    const MasterSurface sphere(body, {g.faces.at("curved")[0]});
    ASSERT_EQ(sphere.num_elements(), parts * parts);
    long visited = 0;
    const int queries = 30;
    for (int k = 0; k < queries; ++k) {
      const Eigen::Vector3d x = radius(rng) * Eigen::Vector3d(unit(rng), unit(rng), -unit(rng)).normalized();
      int candidates = 0;
      const auto fast = sphere.project(x, &candidates);
      visited += candidates;
      ASSERT_TRUE(fast);
      if (parts > 16 || k >= 10) continue;  // (trying every element is the slow part)
      const auto every = sphere.project_by_every_element(x);
      ASSERT_TRUE(every);
      EXPECT_NEAR(fast->distance, every->distance, 1e-13);
      EXPECT_NEAR((fast->x - every->x).norm(), 0, 1e-10);
    }
    per_query.push_back(double(visited) / queries);
  }
  // The bounds are tight: a point near the surface runs Newton on the
  // element under it and hardly another (measured 1.0-1.2; 3.5-4.6 with
  // axis-aligned boxes and a depth-first descent).
  for (double v : per_query) EXPECT_LT(v, 3) << v;
  EXPECT_LT(per_query[2], 1.5 * per_query[0]);
}

TEST(MasterSurface, FindsTheNearestElementFromFarAndFromInsideOnAGradedMesh) {
  // A sphere octant graded as hertz3d's (80 % of the spans in 10 % of one
  // direction: strips 30 times longer than wide, the mesh two-body contact
  // meets). Points far outside, where the distance varies slowly over many
  // elements, and inside near the centre, where every element is almost
  // equally far: the tree finds what trying every element finds, and runs
  // Newton on few (measured 1.7-3.0 per query; 3.2-8.5 with the elements'
  // boxes alone, without their parts').
  const Geometry g = sphere_octant(1.0);
  NurbsPatch patch = elevate_to(g.patch, 3);
  patch = refine_to(patch, 0, KnotVector::graded(3, 32, 0.8, 0.1, true));
  patch = refine_to(patch, 2, KnotVector::uniform(3, 8));
  const Body body(patch);
  const MasterSurface sphere(body, {g.faces.at("curved")[0]});
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.02, 1.0);
  for (const auto [low, high] : {std::pair{1.5, 3.0}, std::pair{1.05, 1.3}, std::pair{0.2, 0.7}}) {
    std::uniform_real_distribution<double> radius(low, high);
    long visited = 0;
    const int queries = 40;
    for (int k = 0; k < queries; ++k) {
      const Eigen::Vector3d x = radius(rng) * Eigen::Vector3d(unit(rng), unit(rng), -unit(rng)).normalized();
      int candidates = 0;
      const auto fast = sphere.project(x, &candidates);
      visited += candidates;
      const auto every = sphere.project_by_every_element(x);
      ASSERT_TRUE(fast && every);
      // (Far from a sphere the nearest point is the radial one.)
      EXPECT_NEAR(fast->distance, every->distance, 1e-12 * every->distance) << low;
      EXPECT_NEAR((fast->x - x.normalized()).norm(), 0, kProjection) << low;
    }
    EXPECT_LT(double(visited) / queries, 5) << low;
  }
}

TEST(MasterSurface, FollowsTheBodyWhenItMoves) {
  const Geometry g = quarter_annulus(1.0, 2.0);
  const Body body = refined(g, 2, 4);
  MasterSurface outer(body, {g.faces.at("outer")[0]});
  Eigen::MatrixXd u(body.num_control_points(), 2);
  u.col(0).setConstant(0.5);
  u.col(1).setConstant(-0.25);
  outer.update(u);
  const Eigen::Vector2d shift(0.5, -0.25), x = Eigen::Vector2d(2.2 * std::cos(0.7), 2.2 * std::sin(0.7)) + shift;
  const auto mp = outer.project(x);
  ASSERT_TRUE(mp);
  EXPECT_NEAR(mp->gap, 0.2, kProjection);
  EXPECT_NEAR((mp->x - shift - 2.0 * (x - shift).normalized()).norm(), 0, kProjection);
}

}  // namespace
}  // namespace igac
