// SPDX-License-Identifier: BSD-3-Clause
// Interfaces whose sides end with different knots after refinement (a knot
// of the file's in one patch only, a grading along a direction the
// neighbour runs the other way) are made conforming by inserting the
// missing knots on both sides (engine/geometry/conforming_interfaces.hpp).
// They were refused with "not conforming ... refine both patches alike".
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "engine/spline/refinement.hpp"
#include "engine/spline/split.hpp"
#include "io/case_file.hpp"
#include "io/gismo_xml.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

namespace fs = std::filesystem;

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / "igac_conforming_interfaces";
  fs::create_directories(dir);
  return dir;
}

MultiPatch two_sectors() { return read_gismo_xml(IGAC_SOURCE_DIR "/tests/data/quarter_disc_two_patches.xml"); }

// The quarter disc's two sectors, held on x = 0 and y = 0, pressed on their
// arcs; `grading` adds a [[mesh.grading]] table.
Model model_of(const MultiPatch& body, const std::string& name, const std::string& grading = "") {
  const fs::path xml = scratch() / (name + ".xml"), toml = scratch() / (name + ".toml");
  write_gismo_xml(body, xml.string());
  std::ofstream(toml) << "[geometry]\nfile = \"" << xml.string()
                      << "\"\n[mesh]\ndegree = 2\nelements = [4, 4]\n" << grading
                      << "[material]\nE = 1.0\nnu = 0.3\n"
                         "[[dirichlet]]\nfaces = [\"0:west\"]\ncomponent = \"x\"\n"
                         "[[dirichlet]]\nfaces = [\"1:north\"]\ncomponent = \"y\"\n"
                         "[[pressure]]\nfaces = [\"0:south\", \"1:south\"]\nvalue = 0.01\n";
  return build_model(read_case(toml.string()));
}

TEST(ConformingInterfaces, AKnotOfOnePatchIsInsertedInItsNeighbour) {
  // Patch 0 carries a knot at v = 0.3 (the file's own: kept by refinement);
  // patch 1 does not.
  MultiPatch one_knot = two_sectors();
  one_knot.patches[0] = refine_to(one_knot.patches[0], 1, KnotVector(2, {0, 0, 0, 0.3, 1, 1, 1}));
  MultiPatch both_knots = one_knot;
  both_knots.patches[1] = refine_to(both_knots.patches[1], 1, KnotVector(2, {0, 0, 0, 0.3, 1, 1, 1}));
  const Model inserted = model_of(one_knot, "one_knot");
  const Model by_hand = model_of(both_knots, "both_knots");
  ASSERT_EQ(inserted.interface_knots.size(), 1u);
  EXPECT_EQ(inserted.interface_knots[0].patch, 1);
  EXPECT_EQ(inserted.interface_knots[0].direction, 1);
  EXPECT_EQ(inserted.interface_knots[0].count, 1);
  EXPECT_TRUE(by_hand.interface_knots.empty());
  // The same mesh as the one conformed by hand: the same solution.
  ASSERT_EQ(inserted.body.num_control_points(), by_hand.body.num_control_points());
  const RunResult a = solve_model(inserted), b = solve_model(by_hand);
  ASSERT_EQ(a.status, "converged");
  ASSERT_EQ(b.status, "converged");
  EXPECT_LE((a.u - b.u).norm(), 1e-12 * b.u.norm());
}

TEST(ConformingInterfaces, AGradingAlongADirectionTheNeighbourRunsBackwards) {
  // Patch 1's v runs from the arc to the centre: the same grading "toward
  // the start" puts its fine layers at the other end of the interface.
  MultiPatch flipped = two_sectors();
  flipped.patches[1] = reversed(flipped.patches[1], 1);
  const std::string grading =
      "[[mesh.grading]]\ndirection = \"v\"\ntoward = \"start\"\nspan_fraction = 0.5\nrange_fraction = 0.2\n";
  const Model m = model_of(flipped, "flipped", grading);
  ASSERT_EQ(m.interface_knots.size(), 2u);
  for (const InsertedKnots& k : m.interface_knots) {
    EXPECT_EQ(k.direction, 1);
    EXPECT_GT(k.count, 0);
  }
  // Both sides of the interface now have the same breakpoints, reflected.
  const auto b0 = m.body.patch(0).knots(1).breakpoints(), b1 = m.body.patch(1).knots(1).breakpoints();
  ASSERT_EQ(b0.size(), b1.size());
  for (size_t i = 0; i < b0.size(); ++i) EXPECT_NEAR(b0[i], 1 - b1[b1.size() - 1 - i], 1e-12);
  EXPECT_EQ(solve_model(m).status, "converged");
}

}  // namespace
}  // namespace igac
