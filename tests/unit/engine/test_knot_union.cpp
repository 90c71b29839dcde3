// SPDX-License-Identifier: BSD-3-Clause
// Refining a patch whose own knots fall on the mesh's breakpoints
// (KnotVector::united_with, used by build_model): a repeated knot on a
// breakpoint keeps its multiplicity, and a knot written with 12 digits is
// that breakpoint, not a second one 3e-13 beside it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "engine/spline/knot_vector.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"

using igac::KnotVector;

namespace {
int multiplicity_at(const KnotVector& kv, double x) {
  int n = 0;
  for (double k : kv.knots()) n += std::abs(k - x) < 1e-9;
  return n;
}
}  // namespace

TEST(KnotUnion, RepeatedKnotOnAMeshBreakpointKeepsItsMultiplicity) {
  const KnotVector kept(2, {0, 0, 0, 0.5, 0.5, 1, 1, 1});  // the two-arc half circle
  const KnotVector target = KnotVector::uniform(2, 6);    // 0.5 is one of its breakpoints
  const KnotVector u = target.united_with(kept);
  EXPECT_EQ(multiplicity_at(u, 0.5), 2);
  EXPECT_EQ(u.breakpoints().size(), 7u);  // 6 elements, no more
  EXPECT_NO_THROW(kept.knots_missing_from(u));
}

TEST(KnotUnion, TwelveDigitKnotIsTheBreakpointItRounds) {
  const KnotVector kept(2, {0, 0, 0, 0.333333333333, 1, 1, 1});
  const KnotVector u = KnotVector::uniform(2, 3).united_with(kept);
  EXPECT_EQ(u.breakpoints().size(), 4u);  // 0, 1/3, 2/3, 1: no sliver element at 1/3
  EXPECT_NO_THROW(kept.knots_missing_from(u));
  EXPECT_EQ(multiplicity_at(u, 1.0 / 3.0), 1);
}

TEST(KnotUnion, NewBreakpointsOfTheFileAreAdded) {
  const KnotVector kept(2, {0, 0, 0, 0.3, 1, 1, 1});
  const KnotVector u = KnotVector::uniform(2, 2).united_with(kept);
  EXPECT_EQ(u.breakpoints().size(), 4u);  // 0, 0.3, 0.5, 1
  EXPECT_NO_THROW(kept.knots_missing_from(u));
}

TEST(KnotUnion, NothingNewGivesTheTargetItself) {
  const KnotVector target = KnotVector::uniform(3, 4);
  const KnotVector kept(3, {0, 0, 0, 0, 1, 1, 1, 1});
  EXPECT_EQ(target.united_with(kept).knots(), target.knots());
}

// The half annulus of two 90-degree arcs at elements = [6, 2]: the double
// knot 0.5 lies on the uniform mesh's breakpoint 3/6 (this stopped with
// "refined knot vector does not contain the original one").
TEST(KnotUnion, HalfAnnulusAtAnEvenElementCountBuilds) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "igac_knot_union";
  std::filesystem::create_directories(dir);
  const std::string xml = std::string(IGAC_SOURCE_DIR) + "/tests/data/half_annulus_double_knot.xml";
  for (int n : {2, 4, 6, 8}) {
    const std::string toml = (dir / "half_annulus.toml").string();
    std::ofstream(toml) << "[geometry]\nfile = \"" << xml << "\"\n[mesh]\ndegree = 2\nelements = [" << n
                        << ", 2]\n[material]\nE = 1.0\nnu = 0.3\n[[dirichlet]]\nfaces = [\"0:west\"]\ncomponent = "
                           "\"x\"\n[[dirichlet]]\nfaces = [\"0:west\"]\ncomponent = \"y\"\n";
    const igac::Model m = igac::build_model(igac::read_case(toml));
    const KnotVector& u = m.body.patch(0).knots(0);
    EXPECT_EQ(int(u.breakpoints().size()) - 1, n) << n << " elements";
    EXPECT_EQ(multiplicity_at(u, 0.5), 2) << n << " elements";
  }
  std::filesystem::remove_all(dir);
}
