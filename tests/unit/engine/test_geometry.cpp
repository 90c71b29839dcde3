// SPDX-License-Identifier: BSD-3-Clause
// Exact geometry: the circles of the quarter disc and of the quarter annulus
// are rational quadratics (Piegl & Tiller 7.5), so their points lie on the
// circle to round-off before and after any refinement; the refined Hertz
// mesh never folds (det J > 0 at every Gauss point); and the face area
// vectors n dA obey the divergence theorem: int_{boundary} n dA = 0 and
// int_{boundary} X . n dA = dim |V| for a closed patch, with n outward.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "engine/assembly.hpp"
#include "engine/discretisation.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/spline/refinement.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"

namespace {

using igac::Face;
using igac::Geometry;
using igac::KnotVector;
using igac::NurbsPatch;

// Distances from the centre agree with the radius to a few ulps of R.
constexpr double kOnCircle = 1e-12;
// The brief's bound for the arc length against pi R / 2.
constexpr double kArcLength = 1e-12;
// Divergence-theorem identities, summed over O(100) face quadrature points
// of size ~1: round-off of the sums.
constexpr double kClosedBoundary = 1e-12;
// Unit normals come from derivatives, which on elements of parametric
// length h carry round-off ~ (p+1) eps p / h relative (h ~ 1e-3 on the
// subdivided graded mesh: ~1e-12 measured); 10x that.
constexpr double kNormalRoundoff = 1e-11;
// p + 1 Gauss points (what assembly uses) are not exact for the rational
// arc; on the 64-element graded Hertz mesh their error is ~5e-12 (measured),
// far below discretisation errors.  This bounds it.
constexpr double kArcLengthAssemblyQuadrature = 1e-10;
// Gauss points per direction for the face integrals below.  The integrands
// are rational (the circle's speed is not polynomial), so no finite rule is
// exact; this many points on elements of angle <= pi/8 leave an error far
// below 1e-12 (Gauss error ~ (h/2)^(2n), n = 12; p + 1 points are not enough
// on the coarse patch).
constexpr int kFacePoints = 12;

std::vector<double> random_params(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U01(0.0, 1.0);
  std::vector<double> u{0.0, 1.0, 0.5};
  for (int i = 0; i < n; ++i) u.push_back(U01(rng));
  return u;
}

// Largest | |X - 0| - r | over points of the face `face` of `patch`.
double circle_error(const NurbsPatch& patch, const Face& face, double r) {
  double err = 0;
  for (double t : random_params(200, 31)) {
    Eigen::VectorXd xi(2);
    xi[face.direction] = face.at_end ? 1.0 : 0.0;
    xi[1 - face.direction] = t;
    err = std::max(err, std::abs(patch.point(xi).norm() - r));
  }
  // The face as its own patch (what face quadrature integrates over).
  const NurbsPatch fp = patch.face_patch(face);
  for (double t : random_params(50, 37)) err = std::max(err, std::abs(fp.point(Eigen::VectorXd::Constant(1, t)).norm() - r));
  return err;
}

// The refinements a run applies: degree elevation, a graded direction as in
// hertz2d.toml, then uniform subdivision.
std::vector<std::pair<std::string, NurbsPatch>> refinements(const NurbsPatch& coarse) {
  std::vector<std::pair<std::string, NurbsPatch>> out{{"coarse", coarse}};
  for (int p : {2, 3, 4}) {
    NurbsPatch q = igac::elevate_to(coarse, p);
    q = igac::refine_to(q, 0, KnotVector::graded(p, 64, 0.8, 0.1, true));
    q = igac::refine_to(q, 1, KnotVector::uniform(p, 16));
    out.emplace_back("degree " + std::to_string(p) + ", graded 64 x 16", q);
    out.emplace_back("degree " + std::to_string(p) + ", graded, subdivided", igac::subdivide(q, 2));
  }
  return out;
}

TEST(Geometry, QuarterDiscArcIsACircleBeforeAndAfterRefinement) {
  for (double R : {1.0, 2.5}) {
    const Geometry g = igac::quarter_disc(R);
    const auto curved = igac::find_faces(g, "curved");
    ASSERT_TRUE(curved && curved->size() == 1);
    const Face arc = curved->front().face;
    EXPECT_EQ(arc, (Face{1, false}));
    // Ends of the arc: A = (0, -R) at u = 0, B = (R, 0) at u = 1.
    EXPECT_LE((g.patch.point(Eigen::Vector2d(0, 0)) - Eigen::Vector2d(0, -R)).norm(), kOnCircle * R);
    EXPECT_LE((g.patch.point(Eigen::Vector2d(1, 0)) - Eigen::Vector2d(R, 0)).norm(), kOnCircle * R);
    for (const auto& [what, patch] : refinements(g.patch)) {
      SCOPED_TRACE(what + ", R = " + std::to_string(R));
      EXPECT_LE(circle_error(patch, arc, R), kOnCircle * R);
    }
  }
}

TEST(Geometry, QuarterAnnulusCirclesBeforeAndAfterRefinement) {
  const double a = 1.0, b = 2.0;
  const Geometry g = igac::quarter_annulus(a, b);
  const Face inner = igac::find_faces(g, "inner")->front().face, outer = igac::find_faces(g, "outer")->front().face;
  for (const auto& [what, patch] : refinements(g.patch)) {
    SCOPED_TRACE(what);
    EXPECT_LE(circle_error(patch, inner, a), kOnCircle * b);
    EXPECT_LE(circle_error(patch, outer, b), kOnCircle * b);
  }
}

// The Hertz mesh exactly as a run builds it (build_model on hertz2d.toml),
// at degree 2 and 3 and one extra refinement: det J > 0 at every Gauss point.
TEST(Geometry, RefinedQuarterDiscHasPositiveJacobianAtEveryGaussPoint) {
  for (int p : {2, 3})
    for (int refine : {0, 1}) {
      SCOPED_TRACE("degree " + std::to_string(p) + ", refine " + std::to_string(refine));
      igac::CaseSpec spec = igac::read_case(IGAC_SOURCE_DIR "/cases/hertz2d.toml");
      igac::apply_overrides(spec, p, refine);
      const igac::Model m = igac::build_model(spec);
      const NurbsPatch& patch = m.body.patch(0);
      EXPECT_EQ(patch.degree(0), p);
      EXPECT_EQ(patch.num_elements(), 64 * 16 << (2 * refine));
      const igac::PatchQuadrature quad(patch, igac::gauss_points_for(p));
      igac::ElementData ed;
      double min_det = std::numeric_limits<double>::infinity();
      int n_points = 0;
      for (int e = 0; e < quad.num_elements(); ++e) {
        quad.evaluate(e, ed, false);
        min_det = std::min(min_det, ed.min_det_J);
        for (int q = 0; q < ed.JxW.size(); ++q) {
          ++n_points;
          ASSERT_GT(ed.JxW[q], 0.0) << "element " << e << ", point " << q;
        }
      }
      EXPECT_EQ(n_points, patch.num_elements() * (p + 1) * (p + 1));
      EXPECT_GT(min_det, 0.0);
      // and the arc of the mesh that is solved is still the circle
      EXPECT_LE(circle_error(patch, Face{1, false}, spec.radius), kOnCircle);
    }
}

struct BoundaryIntegrals {
  Eigen::VectorXd n_dA;  // int n dA over the whole boundary
  double x_dot_n_dA = 0;  // int X . n dA
  double volume = 0;
};

BoundaryIntegrals boundary_integrals(const NurbsPatch& patch, int points) {
  const int dim = patch.space_dim();
  BoundaryIntegrals s{Eigen::VectorXd::Zero(dim)};
  igac::ElementData ed;
  for (int d = 0; d < patch.param_dim(); ++d)
    for (bool at_end : {false, true}) {
      const igac::PatchQuadrature q = igac::face_quadrature(patch, Face{d, at_end}, points);
      for (int e = 0; e < q.num_elements(); ++e) {
        q.evaluate(e, ed, false);
        for (int k = 0; k < ed.JxW.size(); ++k) {
          s.n_dA += ed.normal.row(k).transpose() * ed.JxW[k];
          s.x_dot_n_dA += ed.X.row(k).dot(ed.normal.row(k)) * ed.JxW[k];
        }
      }
    }
  const igac::PatchQuadrature vol(patch, points);
  for (int e = 0; e < vol.num_elements(); ++e) {
    vol.evaluate(e, ed, false);
    s.volume += ed.JxW.sum();
  }
  return s;
}

TEST(Geometry, OutwardNormalIntegratesToZeroOverClosedBoundaries) {
  const double R = 1.0;
  const NurbsPatch disc = igac::subdivide(igac::elevate_to(igac::quarter_disc(R).patch, 3), 4);
  const NurbsPatch annulus = igac::subdivide(igac::quarter_annulus(1.0, 2.0).patch, 4);
  // A rational 3D box: degree 2, random weights and moved control points
  // everywhere (faces included), so every face is curved and rational.
  NurbsPatch box = igac::subdivide(igac::elevate_to(igac::box(1.0, 0.8, 0.6).patch, 2), 2);
  {
    std::mt19937 rng(41);
    std::uniform_real_distribution<double> weight(0.6, 1.6), shift(-0.04, 0.04);
    Eigen::MatrixXd P = box.points();
    Eigen::VectorXd w = box.weights();
    for (int i = 0; i < box.num_control_points(); ++i) {
      w[i] = weight(rng);
      for (int c = 0; c < 3; ++c) P(i, c) += shift(rng);
    }
    box = NurbsPatch(box.all_knots(), P, w);
  }
  const std::vector<std::tuple<std::string, NurbsPatch, double>> shapes{
      {"quarter disc", disc, std::numbers::pi * R * R / 4},
      {"quarter annulus", annulus, std::numbers::pi * (4.0 - 1.0) / 4},
      {"rational box", box, -1.0}};
  for (const auto& [name, patch, exact_volume] : shapes) {
    SCOPED_TRACE(name);
    const BoundaryIntegrals s = boundary_integrals(patch, kFacePoints);
    EXPECT_LE(s.n_dA.norm(), kClosedBoundary) << "int n dA = " << s.n_dA.transpose();
    // Outward orientation: div X = dim, so int X . n dA = dim |V| > 0
    // (all-inward normals would give -dim |V| and still a zero int n dA).
    EXPECT_NEAR(s.x_dot_n_dA, patch.space_dim() * s.volume, kClosedBoundary);
    EXPECT_GT(s.volume, 0.0);
    if (exact_volume > 0) {
      EXPECT_NEAR(s.volume, exact_volume, kClosedBoundary);
    }
  }
}

TEST(Geometry, QuarterDiscArcLengthAndNormal) {
  for (double R : {1.0, 2.5}) {
    const Geometry g = igac::quarter_disc(R);
    for (const auto& [what, patch] : refinements(g.patch)) {
      SCOPED_TRACE(what + ", R = " + std::to_string(R));
      const igac::PatchQuadrature q = igac::face_quadrature(patch, Face{1, false}, std::max(kFacePoints, patch.degree(0) + 1));
      igac::ElementData ed;
      double length = 0, normal_error = 0;
      for (int e = 0; e < q.num_elements(); ++e) {
        q.evaluate(e, ed, false);
        length += ed.JxW.sum();
        // outward unit normal of a circle about the origin: X / R
        for (int k = 0; k < ed.JxW.size(); ++k)
          normal_error = std::max(normal_error, (ed.normal.row(k) - ed.X.row(k) / R).norm());
      }
      EXPECT_NEAR(length, std::numbers::pi * R / 2, kArcLength * R);
      EXPECT_LE(normal_error, kNormalRoundoff);
    }
  }
}

// p + 1 Gauss points (what assembly and the pressure load use) on the Hertz
// mesh give the arc length to within the quadrature error of a rational
// integrand.
TEST(Geometry, QuarterDiscArcLengthWithAssemblyQuadrature) {
  igac::CaseSpec spec = igac::read_case(IGAC_SOURCE_DIR "/cases/hertz2d.toml");
  const igac::Model m = igac::build_model(spec);
  const NurbsPatch& patch = m.body.patch(0);
  const auto arc = igac::find_faces(m, "curved")->front();
  const igac::PatchQuadrature q = igac::face_quadrature(patch, arc, igac::gauss_points_for(patch.degree(0)));
  igac::ElementData ed;
  double length = 0;
  for (int e = 0; e < q.num_elements(); ++e) {
    q.evaluate(e, ed, false);
    length += ed.JxW.sum();
  }
  EXPECT_NEAR(length, std::numbers::pi * spec.radius / 2, kArcLengthAssemblyQuadrature);
}

}  // namespace
