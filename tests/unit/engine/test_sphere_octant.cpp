// SPDX-License-Identifier: BSD-3-Clause
// The exact sphere octant of the 3D Hertz benchmark: the spherical face lies
// on the sphere to round-off before and after refinement, the contact point
// (0, 0, -R) is a regular corner of the contact face, every Gauss point of the
// shipped mesh has det J > 0, and the collapsed face on the x axis shares its
// unknowns so the displacement there is single-valued.
#include <gtest/gtest.h>

#include <random>

#include "engine/assembly.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/spline/refinement.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"

using namespace igac;

namespace {
constexpr double kRoundOff = 1e-12;  // exact rational geometry: only round-off remains
}

TEST(SphereOctant, ContactFaceLiesOnTheSphere) {
  const double R = 1.3;
  const Geometry g = sphere_octant(R);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0, 1);
  for (const NurbsPatch& p : {g.patch, subdivide(elevate_to(g.patch, 3), 3)}) {
    const NurbsPatch face = p.face_patch(Face{1, false});
    for (int k = 0; k < 200; ++k) {
      const Eigen::Vector2d xi(U(rng), U(rng));
      const Eigen::VectorXd X = face.point(xi);
      EXPECT_NEAR(X.norm(), R, kRoundOff * R);
      EXPECT_GE(X[0], -kRoundOff);
      EXPECT_GE(X[1], -kRoundOff);
      EXPECT_LE(X[2], kRoundOff);
    }
  }
}

TEST(SphereOctant, ContactPointIsARegularCornerOfTheContactFace) {
  const Geometry g = sphere_octant(1.0);
  const NurbsPatch face = g.patch.face_patch(Face{1, false});
  const Eigen::VectorXd A = face.point(Eigen::Vector2d(0, 1));
  EXPECT_NEAR((A - Eigen::Vector3d(0, 0, -1)).norm(), 0, kRoundOff);
  // regular: the two face tangents there are orthogonal and nonzero
  const Eigen::MatrixXd T = face.jacobian(Eigen::Vector2d(0, 1));
  EXPECT_GT(T.col(0).norm(), 0.1);
  EXPECT_GT(T.col(1).norm(), 0.1);
  EXPECT_NEAR(T.col(0).dot(T.col(1)), 0, kRoundOff);
}

TEST(SphereOctant, JacobianIsPositiveAtEveryGaussPointOfTheShippedMesh) {
  const Model m = build_model(read_case(std::string(IGAC_SOURCE_DIR) + "/cases/hertz3d.toml"));
  const PatchQuadrature q(m.body.patch(0), 3);
  ElementData ed;
  double min_det = 1e300;
  for (int e = 0; e < q.num_elements(); ++e) {
    q.evaluate(e, ed, false);
    min_det = std::min(min_det, ed.min_det_J);
  }
  EXPECT_GT(min_det, 0.0);
}

TEST(SphereOctant, CollapsedFaceSharesItsUnknowns) {
  const Geometry g = sphere_octant(1.0);
  const NurbsPatch p = subdivide(elevate_to(g.patch, 2), 2);
  const DofMap dofs(p, {});
  // control points on the face u = 1 (the x axis) with the same position
  // have the same equations
  const auto cps = p.face_control_points(Face{0, true});
  int shared = 0;
  for (int a : cps)
    for (int b : cps)
      if (a < b && (p.points().row(a) - p.points().row(b)).norm() < kRoundOff) {
        for (int i = 0; i < 3; ++i) EXPECT_EQ(dofs.equation(a * 3 + i), dofs.equation(b * 3 + i));
        ++shared;
      }
  EXPECT_GT(shared, 0);
  // and a volume integral over the octant gives pi R^3 / 6 (the integrand
  // det J is rational: 8 Gauss points per direction bring it to ~1e-11)
  constexpr double kQuadratureTolerance = 1e-9;
  const PatchQuadrature q(p, 8);
  ElementData ed;
  double V = 0;
  for (int e = 0; e < q.num_elements(); ++e) {
    q.evaluate(e, ed, false);
    V += ed.JxW.sum();
  }
  EXPECT_NEAR(V, M_PI / 6, kQuadratureTolerance);
}
