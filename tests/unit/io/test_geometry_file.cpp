// SPDX-License-Identifier: BSD-3-Clause
// A case reads its body from a G+Smo XML file ([geometry] file = ...): the 2D
// Hertz quarter disc written as a file gives the built-in case's solution to
// round-off, faces answer to PATCH:SIDE names and to names of one's own
// ([faces]), a file's own interior knots survive refinement, and a file with
// a degree above the requested one is refused naming [mesh] degree.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "engine/spline/refinement.hpp"
#include "model/case_body.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "io/gismo_xml.hpp"
#include "tests/support/igac_process.hpp"

namespace igac {
namespace {

namespace fs = std::filesystem;
const std::string kSource = IGAC_SOURCE_DIR;

// hertz2d.toml with its [geometry] table replaced and `from` -> `to` edits.
fs::path hertz_from_file(const fs::path& dir, const std::string& file, std::vector<std::pair<std::string, std::string>> edits = {}) {
  std::string s = igac_test::read_file(kSource + "/cases/hertz2d.toml");
  const auto a = s.find("[geometry]"), b = s.find("[mesh]");
  s.replace(a, b - a, "[geometry]\nfile = \"" + file + "\"\nradius = 1.0\n\n");
  if (edits.empty())  // a file's faces are PATCH:SIDE: curved = v0 (0:south), top = u1 (0:east), left = u0 + v1
    edits = {{"faces = [\"left\"]", "faces = [\"0:west\", \"0:north\"]"},
             {"faces = [\"top\"]", "faces = [\"0:east\"]"},
             {"face = \"curved\"", "face = \"0:south\""}};
  for (const auto& [from, to] : edits) {
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) s.replace(at, from.size(), to);
  }
  const fs::path p = dir / "from_file.toml";
  std::ofstream(p) << s;
  return p;
}

RunResult run(const std::string& path) {
  Model m = build_model(read_case(path));
  return solve_model(m, quiet_run());
}

TEST(GeometryFile, HertzBodyFromAFileEqualsTheBuiltInQuarterDisc) {
  igac_test::TempDir tmp("gfile");
  fs::copy_file(kSource + "/tests/data/quarter_disc.xml", tmp.path() / "disc.xml");
  const RunResult from_file = run(hertz_from_file(tmp.path(), "disc.xml").string());
  const RunResult built_in = run(kSource + "/cases/hertz2d.toml");
  ASSERT_EQ(from_file.status, "converged");
  ASSERT_EQ(from_file.u.rows(), built_in.u.rows());
  EXPECT_LE((from_file.u - built_in.u).cwiseAbs().maxCoeff(), 1e-12 * built_in.u.cwiseAbs().maxCoeff());
  EXPECT_NEAR(from_file.contacts.front().report.max_pressure, built_in.contacts.front().report.max_pressure, 1e-12);
}

TEST(GeometryFile, IgacGeometryRoundTripGivesTheSameRun) {
  igac_test::TempDir tmp("ground");
  const auto o = igac_test::run_igac("geometry " + igac_test::quote(kSource + "/cases/hertz2d.toml") + " --out body.xml",
                                     tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const RunResult again = run(hertz_from_file(tmp.path(), "body.xml").string());
  const RunResult built_in = run(kSource + "/cases/hertz2d.toml");
  EXPECT_LE((again.u - built_in.u).cwiseAbs().maxCoeff(), 1e-12 * built_in.u.cwiseAbs().maxCoeff());
}

TEST(GeometryFile, PatchSideNamesAndFaceSets) {
  igac_test::TempDir tmp("gsides");
  fs::copy_file(kSource + "/tests/data/quarter_disc.xml", tmp.path() / "disc.xml");
  // The built-in names: curved = v0 (0:south), top = u1 (0:east), left = u0 + v1.
  const fs::path c = hertz_from_file(tmp.path(), "disc.xml",
                                     {{"faces = [\"left\"]", "faces = [\"symmetry\"]"},
                                      {"faces = [\"top\"]", "faces = [\"0:east\"]"},
                                      {"face = \"curved\"", "face = \"0:south\""},
                                      {"[[dirichlet]]", "[faces]\nsymmetry = [\"0:west\", \"0:north\"]\n\n[[dirichlet]]"}});
  const RunResult named = run(c.string());
  const RunResult built_in = run(kSource + "/cases/hertz2d.toml");
  ASSERT_EQ(named.status, "converged");
  EXPECT_LE((named.u - built_in.u).cwiseAbs().maxCoeff(), 1e-12 * built_in.u.cwiseAbs().maxCoeff());
}

TEST(GeometryFile, InteriorKnotsOfTheFileSurviveRefinement) {
  // The quarter disc split at u = 0.3 (knot inserted) is the same geometry:
  // the run refines to a knot vector that keeps 0.3, and its solution is
  // that of the built-in body on a mesh with that one extra knot line.
  igac_test::TempDir tmp("gknots");
  MultiPatch body = read_gismo_xml(kSource + "/tests/data/quarter_disc.xml");
  body.patches[0] = refine_to(body.patches[0], 0, KnotVector(2, {0, 0, 0, 0.3, 1, 1, 1}));
  write_gismo_xml(body, (tmp.path() / "knotted.xml").string());
  const RunResult r = run(hertz_from_file(tmp.path(), "knotted.xml").string());
  ASSERT_EQ(r.status, "converged");
  EXPECT_NEAR(r.contacts.front().report.total_force / r.applied_force, 1.0, 1e-10);
  EXPECT_NEAR(r.contacts.front().report.max_pressure / 0.045812, 1.0, 0.01);
}

TEST(GeometryFile, DegreeBelowTheFilesIsRefused) {
  igac_test::TempDir tmp("gdeg");
  const auto g = igac_test::run_igac(
      "geometry " + igac_test::quote(kSource + "/cases/lame_cylinder.toml") + " --out annulus.xml", tmp.path());
  ASSERT_EQ(g.exit_code, 0) << g.output;
  std::string s = igac_test::read_file(kSource + "/cases/lame_cylinder.toml");
  const auto a = s.find("[geometry]"), b = s.find("[mesh]");
  s.replace(a, b - a, "[geometry]\nfile = \"annulus.xml\"\n\n");
  s.replace(s.find("degree = 2"), 10, "degree = 1");
  s.replace(s.find("solution = \"lame\""), 17, "solution = \"none\"");
  std::ofstream(tmp.path() / "annulus.toml") << s;
  const auto o = igac_test::run_igac("run annulus.toml", tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("[mesh] degree = 1 is below the geometry's degree 2"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
}

// The one-patch face names on a two-patch file: "0:east" is now the
// interface between the patches, inside the body; a load there is refused.
TEST(GeometryFile, FaceOnAnInterfaceIsRefusedClearly) {
  igac_test::TempDir tmp("gmulti");
  fs::copy_file(kSource + "/tests/data/quarter_disc_two_patches.xml", tmp.path() / "two.xml");
  const fs::path c = hertz_from_file(tmp.path(), "two.xml");
  const auto o = igac_test::run_igac("run " + igac_test::quote(c.string()), tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  EXPECT_NE(o.output.find("[pressure] faces: '0:east' is the interface patch 0 (east) - patch 1 (west)"),
            std::string::npos)
      << o.output;
}

TEST(GeometryFile, BadFileIsOneLineNamingTheFile) {
  igac_test::TempDir tmp("gbad");
  std::ofstream(tmp.path() / "broken.xml") << "<xml><Geometry type=\"TensorNurbs2\"></xml>";
  const fs::path c = hertz_from_file(tmp.path(), "broken.xml");
  const auto o = igac_test::run_igac("run " + igac_test::quote(c.string()), tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  EXPECT_NE(o.output.find("broken.xml"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace igac
