// SPDX-License-Identifier: BSD-3-Clause
// Pressure penetration ([[pressure]] fluid_entry, contact/pressure_penetration.hpp):
//  - the wet elements are those the entry reaches along the faces, across
//    side boundaries, without crossing a pressed one;
//  - a whole O-ring cross-section (cases/oring_full.xml, plane strain)
//    squeezed between two plates, then pressurised from the left against
//    a wall on the right, frictionless: the fluid stops at the plates'
//    contact bands, and the wall carries exactly the fluid's horizontal
//    force (the plates carry none), to the solve's tolerance; a pressure
//    on the whole closed face instead pushes nowhere;
//  - the same ring axisymmetric (a seal's ring) converges with the front;
//  - in 3D a block squeezed between two plates and pushed by the fluid
//    against a wall: the front crosses the edges between sides, stops at
//    the pressed plates, and the wall carries the fluid's force;
//  - a linear (small-deformation) case refuses it in one line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "contact/pressure_penetration.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

// The ring (radius 2.665 about `centre`) on a plate at y = -2.645 (20 um of
// declared interference: held from the start), a plate above moved down by
// 1 over time 0 -> 1, a wall at x = centre + 3.2, and a pressure p rising
// over 1 -> 2, with `entry` as its fluid_entry line (or none).
std::string ring_case(double centre, const std::string& entry, const std::string& extra = "") {
  const std::string x = std::to_string(centre);
  return "name = \"fluid_ring\"\n" + extra + "[geometry]\nfile = \"" + std::string(IGAC_SOURCE_DIR) +
         "/cases/oring_full.xml\"\ntranslate = [" + x + ", 0.0]\n"
         "[faces]\narcs = [\"0:south\", \"1:south\", \"2:south\", \"3:south\"]\n"
         "[mesh]\ndegree = 2\nelements = [8, 4]\n"
         "[material]\nmodel = \"mooney_rivlin\"\nC10 = 0.37\nC01 = 0.11\nbulk_modulus = 48.0\n"
         "[loading]\nsteps = 10\nmax_increment = 0.1\nmax_newton_iterations = 25\n"
         "[[contact]]\nface = \"arcs\"\ninterference = true\n[contact.obstacle]\ntype = \"plane\"\n"
         "point = [0.0, -2.645]\nnormal = [0.0, 1.0]\n"
         "[[contact]]\nface = \"arcs\"\n[contact.obstacle]\ntype = \"plane\"\npoint = [0.0, 2.665]\n"
         "normal = [0.0, -1.0]\nmotion = [0.0, -1.0]\ncurve = [[0, 0], [1, 1], [2, 1]]\n"
         "[[contact]]\nface = \"arcs\"\n[contact.obstacle]\ntype = \"plane\"\npoint = [" + std::to_string(centre + 3.2) +
         ", 0.0]\nnormal = [-1.0, 0.0]\n"
         "[[pressure]]\nfaces = [\"arcs\"]\nvalue = 0.5\ncurve = [[0, 0], [1, 0], [2, 1]]\n" + entry +
         "[output]\nvtk = false\n";
}

int count(const FaceElementFlags& flags) {
  int n = 0;
  for (const auto& side : flags) n += int(std::count(side.begin(), side.end(), char(1)));
  return n;
}

TEST(PressurePenetration, TheFluidWetsWhatItReachesWithoutCrossingAPressedElement) {
  const Model m = build_model(read_case_text(ring_case(0.0, ""), "fluid_ring.toml"));
  const std::vector<PatchSide> arcs = m.faces.at("arcs");
  ASSERT_EQ(arcs.size(), 4u);  // 0, 1: the right half (lower, upper); 2, 3: the left half
  const FluidFront front(m.body, arcs, Eigen::Vector2d(-2.665, 0.0));
  FaceElementFlags pressed = front.none();
  EXPECT_EQ(count(front.wet(pressed)), 32) << "nothing pressed: the whole closed face";
  pressed[0].assign(8, 1);
  pressed[1].assign(8, 1);
  FaceElementFlags wet = front.wet(pressed);
  EXPECT_EQ(count(wet), 16) << "the right half pressed: the left half wet";
  EXPECT_EQ(count(FaceElementFlags{wet[2], wet[3]}), 16);
  const int s = front.entry_side();
  ASSERT_TRUE(s == 2 || s == 3);
  const int other = 5 - s;
  pressed[size_t(other)][3] = 1;  // a band in the other left quarter stops the fluid there
  wet = front.wet(pressed);
  EXPECT_EQ(wet[size_t(other)][3], 0);
  EXPECT_EQ(count(wet), 8 + 3) << "the entry's quarter, and the other up to the band";
  pressed[size_t(s)][size_t(front.entry_element())] = 1;
  EXPECT_EQ(count(front.wet(pressed)), 0) << "the entry pressed: the fluid enters nowhere";
}

TEST(PressurePenetration, TheWallCarriesTheFluidsForce) {
  const Model m = build_model(read_case_text(ring_case(0.0, "fluid_entry = [-2.665, 0.0]\n"), "fluid_ring.toml"));
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_TRUE(r.status.is_converged()) << r.status.text();
  ASSERT_EQ(r.fluids.size(), 1u);
  const FluidReport& f = r.fluids.front();
  ASSERT_EQ(r.contacts.size(), 3u);
  const double wall = r.contacts[2].report.total_force;
  std::printf("  fluid on %d of %d elements, its force (%.9g, %.3g), the wall's %.9g, peak contact pressure %.4g\n",
              f.wet_elements, f.elements, f.force[0], f.force[1], wall, f.peak_contact_pressure);
  EXPECT_GT(f.wet_elements, 4);
  EXPECT_LT(f.wet_elements, f.elements / 2) << "the fluid stops at the plates' bands on the left";
  EXPECT_NEAR(f.force[0], wall, 1e-8 * wall) << "frictionless plates carry no horizontal force";
  EXPECT_NEAR(f.force[1], 0.0, 1e-8 * wall);
  EXPECT_GT(wall, 0.5 * 0.5 * 2.665) << "p times at least half the ring's height";
  EXPECT_GT(f.peak_contact_pressure, f.pressure) << "the plates hold the fluid";
  // The same pressure on the whole closed face: its resultant is zero, and
  // the wall takes only what the squeeze spreads.
  const RunResult everywhere = solve_model(build_model(read_case_text(ring_case(0.0, ""), "fluid_ring.toml")), quiet_run());
  ASSERT_TRUE(everywhere.status.is_converged()) << everywhere.status.text();
  EXPECT_LT(everywhere.contacts[2].report.total_force, 0.5 * wall);
}

TEST(PressurePenetration, AxisymmetricRingConverges) {
  const Model m = build_model(read_case_text(
      ring_case(10.0, "fluid_entry = [7.335, 0.0]\n", "[model]\nkind = \"axisymmetric\"\n"), "fluid_ring.toml"));
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_TRUE(r.status.is_converged()) << r.status.text();
  ASSERT_EQ(r.fluids.size(), 1u);
  const FluidReport& f = r.fluids.front();
  std::printf("  axisymmetric: fluid on %d of %d elements, radial force %.6g, wall %.6g\n", f.wet_elements, f.elements,
              f.force[0], r.contacts[2].report.total_force);
  EXPECT_GT(f.wet_elements, 4);
  EXPECT_LT(f.wet_elements, f.elements / 2);
  EXPECT_GT(f.force[0], 0.0) << "the fluid pushes the ring outward";
  EXPECT_GT(f.peak_contact_pressure, f.pressure);
}

// A block 1 x 0.5 x 1 (x, y, z), y held on its front face (a symmetry
// plane), on a floor (2e-3 of declared interference), a plate above moved
// down by 0.1 over time 0 -> 1, a wall touching its right face, and a fluid
// pressure of 0.05 on its left, bottom and top faces rising over 1 -> 2,
// entering at the middle of the left face.
std::string block_case() {
  return "name = \"fluid_block\"\n[geometry]\nshape = \"box\"\nsize = [1.0, 0.5, 1.0]\n"
         "[mesh]\ndegree = 2\nelements = [4, 2, 4]\n[material]\nmodel = \"neo_hookean\"\nE = 1.0\nnu = 0.3\n"
         "[loading]\nsteps = 4\nmax_increment = 0.5\nmax_newton_iterations = 25\n"
         "[[dirichlet]]\nfaces = [\"front\"]\ncomponent = \"y\"\n"
         "[[contact]]\nface = \"bottom\"\ninterference = true\n[contact.obstacle]\ntype = \"plane\"\n"
         "point = [0.0, 0.0, 0.002]\nnormal = [0.0, 0.0, 1.0]\n"
         "[[contact]]\nface = \"top\"\n[contact.obstacle]\ntype = \"plane\"\npoint = [0.0, 0.0, 1.0]\n"
         "normal = [0.0, 0.0, -1.0]\nmotion = [0.0, 0.0, -0.1]\ncurve = [[0, 0], [1, 1], [2, 1]]\n"
         "[[contact]]\nface = \"right\"\n[contact.obstacle]\ntype = \"plane\"\npoint = [1.0, 0.0, 0.0]\n"
         "normal = [-1.0, 0.0, 0.0]\n"
         "[[pressure]]\nfaces = [\"left\", \"bottom\", \"top\"]\nvalue = 0.05\ncurve = [[0, 0], [1, 0], [2, 1]]\n"
         "fluid_entry = [0.0, 0.25, 0.5]\n[output]\nvtk = false\n";
}

TEST(PressurePenetration, InThreeDimensionsTheFluidCrossesEdgesBetweenSides) {
  const Model m = build_model(read_case_text(block_case(), "fluid_block.toml"));
  std::vector<PatchSide> faces;
  for (const char* name : {"left", "bottom", "top"}) faces.push_back(m.faces.at(name).at(0));
  const FluidFront front(m.body, faces, Eigen::Vector3d(0.0, 0.25, 0.5));
  EXPECT_EQ(front.entry_side(), 0);
  FaceElementFlags pressed = front.none();
  ASSERT_EQ(count(front.wet(pressed)), 8 + 8 + 8) << "nothing pressed: the left face and, across its edges, both others";
  pressed[2].assign(pressed[2].size(), 1);  // the top pressed
  EXPECT_EQ(count(front.wet(pressed)), 16);
  pressed[1].assign(pressed[1].size(), 1);  // and the bottom
  EXPECT_EQ(count(front.wet(pressed)), 8);
  // one bottom element not pressed: the fluid reaches it when it shares an
  // edge with the left face (the row of 2 along it), else not
  int reached = 0;
  for (size_t e = 0; e < pressed[1].size(); ++e) {
    pressed[1][e] = 0;
    const int wet = count(front.wet(pressed));
    EXPECT_TRUE(wet == 8 || wet == 9) << wet;
    reached += wet == 9;
    pressed[1][e] = 1;
  }
  EXPECT_EQ(reached, 2);
}

TEST(PressurePenetration, InThreeDimensionsTheWallCarriesTheFluidsForce) {
  const RunResult r = solve_model(build_model(read_case_text(block_case(), "fluid_block.toml")), quiet_run());
  ASSERT_TRUE(r.status.is_converged()) << r.status.text();
  ASSERT_EQ(r.fluids.size(), 1u);
  const FluidReport& f = r.fluids.front();
  ASSERT_EQ(r.contacts.size(), 3u);
  const double wall = r.contacts[2].report.total_force;
  std::printf("  3D: fluid on %d of %d elements, its force (%.9g, %.3g, %.3g), the wall's %.9g\n", f.wet_elements,
              f.elements, f.force[0], f.force[1], f.force[2], wall);
  EXPECT_EQ(f.wet_elements, 8) << "the plates press the whole top and bottom: the fluid stops at the left face";
  EXPECT_NEAR(f.force[0], wall, 1e-8 * wall) << "frictionless plates carry no horizontal force";
  EXPECT_NEAR(f.force[2], 0.0, 1e-8 * wall);
  EXPECT_GT(wall, 0.9 * 0.05 * 0.5 * 1.0) << "p times about the left face's area";
}

TEST(PressurePenetration, ALinearCaseRefusesItInOneLine) {
  std::string text = ring_case(0.0, "fluid_entry = [-2.665, 0.0]\n");
  text.replace(text.find("model = \"mooney_rivlin\"\nC10 = 0.37\nC01 = 0.11\nbulk_modulus = 48.0\n"), 66,
               "model = \"linear_elastic\"\nE = 1.0\nnu = 0.3\n");
  try {
    read_case_text(text, "fluid_ring.toml");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("fluid_entry"), std::string::npos) << message;
    EXPECT_NE(message.find("large deformation"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace igac
