// SPDX-License-Identifier: BSD-3-Clause
// [[traction]] in large deformation: a dead traction per unit reference
// area (total Lagrangian: a constant external force, no load stiffness).
//  - A Neo-Hookean block [0, 2] x [0, 1], plane strain, held by symmetry on
//    its left (u_x = 0) and bottom (u_y = 0) faces and pulled by the dead
//    traction T e_x on its right face, deforms homogeneously, F = diag(l1,
//    l2, 1), with the first Piola-Kirchhoff stress P11 = T, P22 = 0:
//      mu (l1 - 1/l1) + lambda ln(l1 l2) / l1 = T,
//      mu (l2 - 1/l2) + lambda ln(l1 l2) / l2 = 0,
//    which quadratic NURBS represent exactly: every control point moves by
//    ((l1 - 1) X, (l2 - 1) Y) to the solver's tolerance.  (A follower load
//    would pull with T l2 per unit reference height, 27 % less here.)
//  - The supports carry the applied force, T times the reference face's
//    length, whatever the deformation: to round-off, for a pull and for a
//    traction oblique to the face.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <Eigen/Dense>

#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

constexpr double kE = 1.0, kNu = 0.3;

std::string block_case(double tx, double ty) {
  return "name = \"dead_traction\"\n[geometry]\nshape = \"rectangle\"\nsize = [2.0, 1.0]\n[mesh]\ndegree = 2\n"
         "elements = [4, 2]\n[material]\nmodel = \"neo_hookean\"\nE = 1.0\nnu = 0.3\n"
         "[[dirichlet]]\nfaces = [\"left\"]\ncomponent = \"x\"\n[[dirichlet]]\nfaces = [\"bottom\"]\ncomponent = \"y\"\n"
         "[[traction]]\nfaces = [\"right\"]\nvalue = [" + std::to_string(tx) + ", " + std::to_string(ty) + "]\n"
         "[loading]\nsteps = 4\n[output]\nvtk = false\n";
}

Model block_model(double tx, double ty) {
  Model m = build_model(read_case_text(block_case(tx, ty), "dead_traction.toml"));
  return m;
}

// (l1, l2) of the plane-strain uniaxial dead traction T (Newton on the two equations above).
Eigen::Vector2d uniaxial_stretches(double T) {
  const double mu = kE / (2 * (1 + kNu)), lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu));
  Eigen::Vector2d l(1, 1);
  for (int it = 0; it < 50; ++it) {
    const double a = l[0], b = l[1], lnJ = std::log(a * b);
    const Eigen::Vector2d r(mu * (a - 1 / a) + lambda * lnJ / a - T, mu * (b - 1 / b) + lambda * lnJ / b);
    Eigen::Matrix2d J;
    J << mu * (1 + 1 / (a * a)) + lambda * (1 - lnJ) / (a * a), lambda / (a * b),  //
        lambda / (a * b), mu * (1 + 1 / (b * b)) + lambda * (1 - lnJ) / (b * b);
    l -= J.partialPivLu().solve(r);
    if (r.norm() < 1e-15) break;
  }
  return l;
}

Eigen::VectorXd reaction(const RunResult& r, const std::string& face) {
  for (const FaceReaction& f : r.dirichlet_reactions)
    if (f.face == face) return f.force;
  ADD_FAILURE() << "no reaction of " << face;
  return Eigen::Vector2d::Zero();
}

TEST(DeadTraction, NeoHookeanBlockMatchesTheUniaxialClosedForm) {
  constexpr double T = 0.3;  // a stretch of 1.33 along x
  const Model m = block_model(T, 0.0);
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  const Eigen::Vector2d l = uniaxial_stretches(T);
  EXPECT_GT(l[0], 1.3);
  double error = 0;
  for (int a = 0; a < m.body.num_control_points(); ++a) {
    const Eigen::RowVector2d X = m.body.points().row(a);
    error = std::max(error, (r.u.row(a) - Eigen::RowVector2d((l[0] - 1) * X[0], (l[1] - 1) * X[1])).norm());
  }
  std::printf("  dead traction %.2f: l1 %.12f, l2 %.12f, max control-point error %.2e\n", T, l[0], l[1], error);
  EXPECT_LT(error, 1e-10);
  // the supports hold T times the reference height 1
  const Eigen::VectorXd left = reaction(r, "left");
  std::printf("  reaction on the left face %.17g (applied %.17g)\n", left[0], -T);
  EXPECT_NEAR(left[0], -T, 1e-14);
}

TEST(DeadTraction, SupportsCarryTheAppliedForceToRoundOff) {
  constexpr double tx = 0.2, ty = 0.01;  // oblique: the block stretches and shears
  const Model m = block_model(tx, ty);
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  const Eigen::VectorXd left = reaction(r, "left"), bottom = reaction(r, "bottom");
  std::printf("  reactions: x %.17g (applied %.17g), y %.17g (applied %.17g)\n", left[0], -tx, bottom[1], -ty);
  EXPECT_NEAR(left[0], -tx, 1e-14);
  EXPECT_NEAR(bottom[1], -ty, 1e-14);
}

}  // namespace
}  // namespace igac
