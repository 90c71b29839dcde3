// SPDX-License-Identifier: BSD-3-Clause
// Reaction forces of the Dirichlet face sets (model/reactions.hpp): on a
// body in equilibrium they balance the loads and the contact force.
#include <gtest/gtest.h>

#include <string>

#include "engine/assembly.hpp"
#include "engine/face_quadrature.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/reactions.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

const std::string kCases = std::string(IGAC_SOURCE_DIR) + "/cases/";

// A shipped case, built and solved (quietly).
struct Solved {
  Model model;
  RunResult result;
};
Solved solved(const std::string& name) {
  Solved s{build_model(read_case(kCases + name + ".toml")), {}};
  s.result = solve_model(s.model, quiet_run());
  return s;
}

const FaceReaction& reaction_of(const RunResult& r, const std::string& face) {
  for (const FaceReaction& f : r.dirichlet_reactions)
    if (f.face == face) return f;
  throw std::runtime_error("no reaction of " + face);
}

// Lame's thick cylinder: the internal pressure p = 1 on the quarter arc of
// radius 1 pushes the body with (p, p); the two symmetry cuts hold it, the
// cut x = 0 along x and the cut y = 0 along y.  The reactions balance the
// pressure's resultant (the same quadrature) to round-off, and the
// resultant of the exact circle is (1, 1) to the quadrature's accuracy.
TEST(DirichletReactions, BalanceThePressureOnLamesCylinder) {
  const Solved s = solved("lame_cylinder");
  const Model& m = s.model;
  const RunResult& r = s.result;
  ASSERT_EQ(r.status, "converged");
  ASSERT_EQ(r.dirichlet_reactions.size(), 2u);
  Eigen::VectorXd load = Eigen::VectorXd::Zero(2);  // int -p n dGamma
  FaceQuadrature(m.body, *find_faces(m, "inner"), gauss_points_for(m.body.degree()))
      .for_each_element([&](int, const auto& v) {
        for (int k = 0; k < v.n_q; ++k) load -= (1.0 * v.normal[k] * v.JxW[k]).head(2);
      });
  const Eigen::VectorXd left = reaction_of(r, "left").force, bottom = reaction_of(r, "bottom").force;
  EXPECT_EQ(left[1], 0.0);  // "left" prescribes x only
  EXPECT_EQ(bottom[0], 0.0);
  EXPECT_NEAR(left[0] + load[0], 0.0, 1e-12);
  EXPECT_NEAR(bottom[1] + load[1], 0.0, 1e-12);
  EXPECT_NEAR(left[0], -1.0, 1e-6);
  EXPECT_NEAR(bottom[1], -1.0, 1e-6);
  EXPECT_NEAR(r.applied_force, load.norm(), 1e-12);  // a pressure-loaded case: its resultant, as before
}

// Hertz in small deformation: the pressure on top is carried by the
// obstacle, the symmetry cut carries no vertical force (it holds x only)
// and, the obstacle being a plane y = const, no horizontal one either.
TEST(DirichletReactions, SymmetryCutOfHertzCarriesNothing) {
  const Solved s = solved("hertz2d");
  const RunResult& r = s.result;
  ASSERT_EQ(r.status, "converged");
  ASSERT_EQ(r.dirichlet_reactions.size(), 1u);
  const Eigen::VectorXd f = r.dirichlet_reactions.front().force;
  EXPECT_EQ(f[1], 0.0);
  EXPECT_NEAR(f[0], 0.0, 1e-10 * r.applied_force);
}

// Large deformation, driven by a prescribed displacement of the top face:
// its reaction is (minus) the force pressing the body on the plane, which the
// contact carries (to Newton's tolerance), and it is the case's applied
// force (it was 0.0).  Per step too: every load-curve point has it.
TEST(FiniteStrainCases, DisplacementDrivenReactionIsTheContactForce) {
  const Solved s = solved("hertz2d_neohookean_displacement");
  const RunResult& r = s.result;
  ASSERT_EQ(r.status, "converged");
  const double contact = r.contacts.front().report.total_force;
  const Eigen::VectorXd top = reaction_of(r, "top").force;
  ASSERT_GT(contact, 0.0);
  EXPECT_NEAR(-top[1], contact, 1e-8 * contact);  // the support pulls the face down
  EXPECT_NEAR(r.applied_force, contact, 1e-8 * contact);
  ASSERT_FALSE(r.load_curve.empty());
  for (const LoadCurvePoint& p : r.load_curve) {
    ASSERT_EQ(p.dirichlet_reactions.size(), r.dirichlet_reactions.size());
    double top_y = 0;
    for (const FaceReaction& f : p.dirichlet_reactions)
      if (f.face == "top") top_y = f.force[1];
    EXPECT_NEAR(-top_y, p.contact_force(), 1e-7 * std::max(contact, 1e-300)) << "t = " << p.load_factor;
  }
}

}  // namespace
}  // namespace igac
