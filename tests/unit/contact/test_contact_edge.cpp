// SPDX-License-Identifier: BSD-3-Clause
// The contact edge a reported as the half width (ContactPressure::
// edge_along), on multipliers that represent Hertz's p = p0 sqrt(1 - r^2/a^2)
// exactly as the discrete space can: S0 (p = 2) the element means, S1
// (p = 3) the nodal values.  The edge is interpolated from the pressure
// (the sqrt shape of a smooth edge fitted to the last two pressed values),
// so it is found well inside an element, where the extent of the pressed
// multipliers' anchors (what was reported before) is off by up to half an
// element or more; a contact point inside the face (no symmetry plane: a
// roller between plates) and at its corner (a symmetry plane) alike.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "contact/pressure.hpp"
#include "contact/weighted_gap.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/spline/refinement.hpp"

namespace {

using namespace igac;

constexpr double kLength = 2.0;
constexpr double kP0 = 1.0;
// Measured: S1 exact to round-off (the elliptic fit is exact on Hertz's
// nodal values), S0 within 0.0113 h (the ellipse through element means);
// 0.05 h, a margin of 4.4.  A pressed multiplier's anchor is an element's
// centre (S0) or a breakpoint (S1): half an element or more from a.
constexpr double kElementFraction = 0.05;

double hertz(double r, double a) { return r < a ? kP0 * std::sqrt(1 - r * r / (a * a)) : 0.0; }

// The bottom side of a 2 x 0.5 rectangle of degree p with n elements along
// it, and multipliers -p_h of Hertz's profile centred at x0 with edge a.
struct Setup {
  NurbsPatch patch;
  std::unique_ptr<ContactFace> face;
  Eigen::VectorXd lambda, weights;
  double h = 0;
  Setup(int p, int n, double x0, double a) {
    patch = elevate_to(rectangle(kLength, 0.5).patch, p);
    patch = refine_to(patch, 0, KnotVector::uniform(p, n));
    face = std::make_unique<ContactFace>(patch, Face{1, false});  // y = 0
    const ContactSide& side = face->sides[0];
    const int m = face->num_multipliers();
    lambda.resize(m);
    weights = Eigen::VectorXd::Ones(m);
    h = kLength / n;
    const std::vector<double> b = side.face_patch.knots(0).breakpoints();
    for (int K = 0; K < m; ++K) {
      if (side.space.degree() == 0) {  // the element mean, by a fine midpoint rule
        constexpr int kPoints = 400;
        double sum = 0;
        for (int i = 0; i < kPoints; ++i) {
          const double t = b[K] + (b[K + 1] - b[K]) * (i + 0.5) / kPoints;
          sum += hertz(std::abs(side.face_patch.point(Eigen::VectorXd::Constant(1, t))[0] - x0), a);
        }
        lambda[K] = -sum / kPoints;
      } else {  // continuous linears: the nodal value at the anchor (a breakpoint)
        const double x = side.face_patch.point(side.space.anchor(K))[0];
        lambda[K] = -hertz(std::abs(x - x0), a);
      }
    }
  }
  double half_width(double x0) const {
    Eigen::VectorXd X0(2), n(2);
    X0 << x0, 0.0;
    n << 0.0, 1.0;  // a plane below the face
    const ContactPressure cp(*face, lambda, weights, std::vector<char>(size_t(lambda.size()), 1), X0, n);
    return cp.report().half_width;
  }
};

void expect_edge_found(int p, double x0) {
  double worst = 0;  // |found - a| / h
  for (int n : {32, 64}) {
    for (double a : {0.3, 0.337, 0.371}) {
      const Setup s(p, n, x0, a);
      const double found = s.half_width(x0);
      worst = std::max(worst, std::abs(found - a) / s.h);
      EXPECT_NEAR(found, a, kElementFraction * s.h) << "p = " << p << ", " << n << " elements, a = " << a;
    }
  }
  std::printf("p = %d, x0 = %g: the edge within %.3g h of a\n", p, x0, worst);
}

TEST(ContactEdge, S0InsideTheFace) { expect_edge_found(2, 1.0); }
TEST(ContactEdge, S1InsideTheFace) { expect_edge_found(3, 1.0); }
TEST(ContactEdge, S0AtTheCorner) { expect_edge_found(2, 0.0); }
TEST(ContactEdge, S1AtTheCorner) { expect_edge_found(3, 0.0); }
// Off the middle of an element and off-centre on the face.
TEST(ContactEdge, S0InsideAnElement) { expect_edge_found(2, 0.77); }
TEST(ContactEdge, S1InsideAnElement) { expect_edge_found(3, 0.77); }

}  // namespace
