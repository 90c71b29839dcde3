// SPDX-License-Identifier: BSD-3-Clause
// The cells of segmented mortar integration in 3D (contact/mortar_cells.hpp):
//  - the collapsed triangle rule integrates monomials of degree 2n - 2
//    exactly (int r^a s^b = a! b! / (a + b + 2)! on the unit triangle);
//  - the cells of a cut slave element tile it: their areas sum to its area
//    to round-off, on aligned and on turned non-matching meshes, and on a
//    slave that overhangs the master's edge; the weights of the whole face
//    sum to its area;
//  - at a current position an element far from the master is not cut.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <omp.h>

#include "contact/mortar_cells.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/quadrature.hpp"
#include "engine/spline/refinement.hpp"

namespace igac {
namespace {

constexpr double kRoundOff = 1e-13;

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

TEST(TriangleRule, IntegratesMonomialsOfDegreeTwoNMinusTwoExactly) {
  for (int n = 1; n <= 6; ++n) {
    const TensorGaussRule rule = triangle_gauss_rule(n);
    for (int a = 0; a <= 2 * n - 2; ++a)
      for (int b = 0; a + b <= 2 * n - 2; ++b) {
        double sum = 0;
        for (size_t q = 0; q < rule.points.size(); ++q)
          sum += rule.weights[q] * std::pow(rule.points[q][0], a) * std::pow(rule.points[q][1], b);
        // (weights sum to 1: the mean over the triangle of area 1/2)
        EXPECT_NEAR(sum, 2 * factorial(a) * factorial(b) / factorial(a + b + 2), kRoundOff) << n << " " << a << " " << b;
      }
  }
}

// A flat box face: [x0, x0 + size]^2 at height z, n x n elements of degree
// p, turned by `angle` about the vertical through (0.5, 0.5).
NurbsPatch box3(int p, int n, double x0, double size, double z0, double height, double angle = 0) {
  NurbsPatch b = elevate_to(box(size, size, height).patch, p);
  for (int d : {0, 1}) b = refine_to(b, d, KnotVector::uniform(p, n));
  Eigen::MatrixXd P = b.points();
  const double c = std::cos(angle), s = std::sin(angle);
  for (int i = 0; i < P.rows(); ++i) {
    const double x = P(i, 0) + x0 - 0.5, y = P(i, 1) + x0 - 0.5;
    P(i, 0) = 0.5 + c * x - s * y;
    P(i, 1) = 0.5 + s * x + c * y;
    P(i, 2) += z0;
  }
  return NurbsPatch(b.all_knots(), P, b.weights());
}

struct Coverage {
  int elements = 0, cut = 0, cells = 0;
  double worst = 0;  // largest |sum of cell areas - 1| of a cut element
  double face = 0;   // sum of the weights (parameter area) of the whole face
};

Coverage cover(const NurbsPatch& slave_box, const NurbsPatch& master_box) {
  const Body body({slave_box, master_box}, {});
  const ContactSide side(body, PatchSide{0, Face{2, false}}, 0);
  const MasterSurface master(body, {PatchSide{1, Face{2, true}}});
  const BezierMesh mesh(side.face_patch);
  Coverage out;
  std::vector<MortarCell> cells;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    ++out.elements;
    if (!mortar_cells(mesh, e, master, cells)) continue;
    ++out.cut;
    out.cells += int(cells.size());
    double sum = 0;
    for (const MortarCell& c : cells) sum += polygon_area(c.polygon);
    out.worst = std::max(out.worst, std::abs(sum - 1));
  }
  std::vector<Eigen::VectorXd> xi;
  std::vector<double> w;
  segmented_side_rule(side, nullptr, master, 4, xi, w);
  for (double x : w) out.face += x;
  return out;
}

TEST(MortarCells, TileEachSlaveElementToRoundOff) {
  // 3 x 3 slave elements on 4 x 4: breakpoints 0, 1/4, 1/3, 1/2, 2/3, 3/4, 1
  // give 2 x 2 cells per slave element, each cut in its two triangles.
  const Coverage aligned = cover(box3(2, 3, 0, 1, 1, 0.5), box3(3, 4, 0, 1, 0, 1));
  EXPECT_EQ(aligned.cut, 9);
  EXPECT_GE(aligned.cells, 36);
  EXPECT_LT(aligned.worst, kRoundOff);
  EXPECT_NEAR(aligned.face, 1.0, kRoundOff);
  // 5 x 5 on 4 x 4: elements cut in one direction, in two, or not.
  const Coverage five = cover(box3(2, 5, 0, 1, 1, 0.5), box3(2, 4, 0, 1, 0, 1));
  EXPECT_EQ(five.cut, 25 - 4);
  EXPECT_LT(five.worst, kRoundOff);
  EXPECT_NEAR(five.face, 1.0, kRoundOff);
  // Turned by 30 degrees on a larger master of 7 x 7.
  const Coverage turned = cover(box3(2, 4, 0, 1, 1, 0.5, std::numbers::pi / 6), box3(2, 7, -0.5, 2, 0, 1));
  EXPECT_GE(turned.cut, 12);
  EXPECT_LT(turned.worst, kRoundOff);
  EXPECT_NEAR(turned.face, 1.0, kRoundOff);
}

TEST(MortarCells, AnElementBeyondTheMastersEdgeIsCutWhereItsProjectionCrossesABreakpoint) {
  // The slave [0.5, 1.5]^2 in 4 x 4 elements on the master [0, 1]^2 of 3 x 3:
  // beyond x = 1 or y = 1 the points project on the master's edge, and the
  // elements there are cut where that projection crosses y = 2/3 (x = 2/3).
  const Coverage c = cover(box3(2, 4, 0.5, 1, 1, 0.5), box3(2, 3, 0, 1, 0, 1));
  EXPECT_EQ(c.elements, 16);
  EXPECT_EQ(c.cut, 7);  // those over x or y in [0.5, 0.75] (holding 2/3): 4 + 4 - 1
  EXPECT_LT(c.worst, kRoundOff);
  EXPECT_NEAR(c.face, 1.0, kRoundOff);
}

TEST(MortarCells, TheSegmentedRuleIsTheSameOnOneThreadAsOnSeveral) {
  // The slave elements are cut in parallel and their points joined in
  // element order: the same points and weights, to the bit, on any number
  // of threads (5 x 5 turned by 30 degrees on 7 x 7: most elements cut).
  const Body body({box3(2, 5, 0, 1, 1, 0.5, std::numbers::pi / 6), box3(2, 7, -0.5, 2, 0, 1)}, {});
  const ContactSide side(body, PatchSide{0, Face{2, false}}, 0);
  const MasterSurface master(body, {PatchSide{1, Face{2, true}}});
  std::vector<Eigen::VectorXd> xi_one, xi_two, xi_five;
  std::vector<double> w_one, w_two, w_five;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  segmented_side_rule(side, nullptr, master, 4, xi_one, w_one);
  omp_set_num_threads(2);
  segmented_side_rule(side, nullptr, master, 4, xi_two, w_two);
  omp_set_num_threads(5);
  segmented_side_rule(side, nullptr, master, 4, xi_five, w_five);
  omp_set_num_threads(threads);
  ASSERT_GT(xi_one.size(), size_t(25 * 16));  // more points than the uncut tensor rule
  EXPECT_TRUE(xi_two == xi_one && xi_five == xi_one);
  EXPECT_TRUE(w_two == w_one && w_five == w_one);
}

// At a current position (large deformation) an element farther from the
// master than its diameter is integrated whole: its multipliers cannot be
// active in that state.  In the reference position every element is cut,
// however far: a small-deformation rule serves the whole solve.
TEST(MortarCells, AFarElementIsCutInTheReferencePositionOnly) {
  // 5 x 5 turned by 30 degrees on 7 x 7 (most elements cut when touching);
  // element diameter 0.2 sqrt(2) = 0.28.
  const auto points = [](double lift, bool current) {
    const Body body({box3(2, 5, 0, 1, 1 + (current ? 0 : lift), 0.5, std::numbers::pi / 6), box3(2, 7, -0.5, 2, 0, 1)},
                    {});
    const ContactSide side(body, PatchSide{0, Face{2, false}}, 0);
    const MasterSurface master(body, {PatchSide{1, Face{2, true}}});
    Eigen::MatrixXd u = Eigen::MatrixXd::Zero(side.face_patch.points().rows(), 3);
    u.col(2).setConstant(lift);
    std::vector<Eigen::VectorXd> xi;
    std::vector<double> w;
    segmented_side_rule(side, current ? &u : nullptr, master, 4, xi, w);
    double face = 0;
    for (double x : w) face += x;
    EXPECT_NEAR(face, 1.0, kRoundOff);
    return xi.size();
  };
  const size_t uncut = 25 * 16;
  EXPECT_GT(points(0.0, true), uncut);   // touching: cut
  EXPECT_GT(points(0.2, true), uncut);   // nearer than a diameter: cut
  EXPECT_EQ(points(0.5, true), uncut);   // farther: the tensor rule on every element
  EXPECT_GT(points(0.5, false), uncut);  // as far, in the reference position: cut
}

}  // namespace
}  // namespace igac
