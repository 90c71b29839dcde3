// SPDX-License-Identifier: BSD-3-Clause
// Self-contact: a [contact] whose master is a face of the slave's own body
// (model/build_model.cpp).  The body is a U of six bilinear patches
// (tests/data/u_shape.xml: a base 2.1 x 1 and two arms 1 x 2 with a gap
// of 0.1 between them); its arms' outer faces are pushed inward by 0.08
// each, so their inner faces close and press on each other near the tips.
// By symmetry the arms meet on x = 0, which is the half model
// (tests/data/u_shape_half.xml: the left arm and half the base, held on
// x = 0) pressed on a rigid plane x = 0, with the same mesh:
//  - small deformation: the contact force, the peak pressure and the
//    reaction of the pushed face equal the half model's to the solve's
//    round-off (flat faces, matching meshes: the segmented mortar is
//    exact);
//  - large deformation (Neo-Hookean): equal to 1e-4.  Not to round-off:
//    the half model's partner is a plane, the U's is the other arm's
//    deformed face, curved where it bends, and the weighted gaps of the
//    multipliers that straddle the contact's edge see the difference
//    (1.7e-5 here, 2.9e-7 with every span halved: it goes with the mesh);
//  - friction (0.2): the arms slide together, so the stuck multipliers
//    carry no shear and the normal force is the frictionless one;
//  - a master_motion on a self-contact is refused in one line.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

const std::string kData = std::string(IGAC_SOURCE_DIR) + "/tests/data/";

std::string u_case(const std::string& law, const std::string& contact_extra = "") {
  return "name = \"u\"\n[geometry]\nfile = \"u_shape.xml\"\n[mesh]\ndegree = 2\nelements = [4, 8]\n"
         "[material]\nmodel = \"" + law + "\"\nE = 1.0\nnu = 0.3\n"
         "[[dirichlet]]\nfaces = [\"0:south\", \"1:south\", \"2:south\", \"3:south\"]\ncomponent = \"x\"\n"
         "[[dirichlet]]\nfaces = [\"0:south\", \"1:south\", \"2:south\", \"3:south\"]\ncomponent = \"y\"\n"
         "[[dirichlet]]\nfaces = [\"4:west\"]\ncomponent = \"x\"\nvalue = 0.08\n"
         "[[dirichlet]]\nfaces = [\"5:east\"]\ncomponent = \"x\"\nvalue = -0.08\n"
         "[contact]\nface = \"4:east\"\nmaster = \"5:west\"\n" + contact_extra;
}

std::string half_case(const std::string& law) {
  return "name = \"u_half\"\n[geometry]\nfile = \"u_shape_half.xml\"\n[mesh]\ndegree = 2\nelements = [4, 8]\n"
         "[material]\nmodel = \"" + law + "\"\nE = 1.0\nnu = 0.3\n"
         "[[dirichlet]]\nfaces = [\"0:south\", \"1:south\"]\ncomponent = \"x\"\n"
         "[[dirichlet]]\nfaces = [\"0:south\", \"1:south\"]\ncomponent = \"y\"\n"
         "[[dirichlet]]\nfaces = [\"1:east\"]\ncomponent = \"x\"\n"
         "[[dirichlet]]\nfaces = [\"2:west\"]\ncomponent = \"x\"\nvalue = 0.08\n"
         "[contact]\nface = \"2:east\"\n[contact.obstacle]\ntype = \"plane\"\npoint = [0.0, 0.0]\nnormal = [-1.0, 0.0]\n";
}

RunResult run(const std::string& text) {
  const Model m = build_model(read_case_text(text, kData + "u.toml"));
  RunResult r = solve_model(m, quiet_run());
  EXPECT_TRUE(r.status.is_converged()) << r.status.text();
  return r;
}

double pushed_face_force(const RunResult& r, const std::string& face) {
  for (const FaceReaction& f : r.dirichlet_reactions)
    if (f.face == face) return f.force[0];
  ADD_FAILURE() << "no reaction of " << face;
  return NAN;
}

void expect_as_half_model(const std::string& law, double tolerance) {
  const RunResult u = run(u_case(law)), half = run(half_case(law));
  ASSERT_FALSE(u.contacts.empty());
  ASSERT_FALSE(half.contacts.empty());
  const double force = u.contacts.front().report.total_force, expected = half.contacts.front().report.total_force;
  std::printf("  %s: U %.12g, half model on a plane %.12g (%.1e)\n", law.c_str(), force, expected,
              std::abs(force / expected - 1));
  EXPECT_GT(expected, 0.04) << "the arms press";
  EXPECT_NEAR(force, expected, tolerance * expected);
  EXPECT_NEAR(u.contacts.front().report.max_pressure, half.contacts.front().report.max_pressure,
              tolerance * half.contacts.front().report.max_pressure);
  EXPECT_NEAR(pushed_face_force(u, "4:west"), pushed_face_force(half, "2:west"), tolerance * expected);
  EXPECT_NEAR(pushed_face_force(u, "5:east"), -pushed_face_force(half, "2:west"), tolerance * expected);
  EXPECT_EQ(u.contacts.front().report.active, half.contacts.front().report.active);
}

TEST(SelfContact, SmallDeformationUIsTheHalfModelOnItsSymmetryPlane) { expect_as_half_model("linear_elastic", 1e-10); }

TEST(SelfContact, LargeDeformationUIsTheHalfModelToTheCurvedPartnersDifference) {
  expect_as_half_model("neo_hookean", 1e-4);
}

TEST(SelfContact, ArmsThatSlideTogetherCarryNoShear) {
  const RunResult frictionless = run(u_case("linear_elastic"));
  const RunResult r = run(u_case("linear_elastic", "friction = 0.2\n"));
  ASSERT_FALSE(r.reactions.empty());
  const double N = r.contacts.front().report.total_force;
  EXPECT_NEAR(N, frictionless.contacts.front().report.total_force, 1e-10 * N);
  ASSERT_GT(r.reactions.front().tangential_force.size(), 0);
  EXPECT_LT(r.reactions.front().tangential_force.norm(), 1e-12 * N);
}

TEST(SelfContact, MasterMotionOnItsOwnBodyIsRefused) {
  try {
    build_model(read_case_text(u_case("linear_elastic", "master_motion = [0.1, 0.0]\n"), kData + "u.toml"));
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("master_motion moves the master's body"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace igac
