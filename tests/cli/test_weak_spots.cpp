// SPDX-License-Identifier: BSD-3-Clause
// Weak spots of issue 21, each failed before its fix: a contact face
// perpendicular to its obstacle, --out a dangling symbolic link, a law's
// constant that overflows blamed on E, a small-deformation run far beyond
// small deformation, a thin held body called not held, and large-deformation
// runs that nothing loads or holds.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;
using igac_test::Outcome;
using igac_test::quote;
using igac_test::run_igac;
using igac_test::TempDir;

// A rectangle [0, L] x [0, H] of degree 2, nu = 0.3, with `rest` appended.
fs::path rectangle_case(const fs::path& dir, double L, double H, const std::string& elements, const std::string& rest,
                        const std::string& material = "E = 1.0\nnu = 0.3\n") {
  const fs::path c = dir / "case.toml";
  std::ofstream(c) << "name = \"rect\"\n[geometry]\nshape = \"rectangle\"\nsize = [" << L << ", " << H
                   << "]\n[mesh]\ndegree = 2\nelements = " << elements << "\n[material]\n" << material << rest;
  return c;
}

nlohmann::json summary(const fs::path& out) { return igac_test::read_summary(out); }

TEST(WeakSpots, ContactFacePerpendicularToTheObstacleIsRefused) {
  TempDir tmp("perpendicular");
  // The right face (normal +x) on a plane whose normal is +y: it can only slide.
  const fs::path c = rectangle_case(tmp.path(), 1, 1, "[4, 4]",
                                    "[[dirichlet]]\nfaces = [\"left\"]\ncomponent = \"x\"\n"
                                    "[[dirichlet]]\nfaces = [\"bottom\"]\ncomponent = \"y\"\n"
                                    "[[pressure]]\nfaces = [\"top\"]\nvalue = 0.01\n"
                                    "[contact]\nface = \"right\"\n[contact.obstacle]\ntype = \"plane\"\n"
                                    "point = [0.0, -0.5]\nnormal = [0.0, 1.0]\n");
  const Outcome o = run_igac("run " + quote(c.string()) + " --quiet --out out", tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("[contact] face 'right' and its obstacle: the contact face is perpendicular to the obstacle"),
            std::string::npos) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
}

TEST(WeakSpots, OutIntoADanglingSymbolicLinkIsRefusedBeforeTheSolve) {
  TempDir tmp("dangling");
  fs::create_symlink(tmp.path() / "nowhere" / "results", tmp.path() / "link");
  const Outcome o = run_igac("run " + quote(std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml") + " --out link",
                             tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(o.output.rfind("igac: error: --out 'link': ", 0), 0u) << o.output;
  EXPECT_NE(o.output.find("is a symbolic link to " + (tmp.path() / "nowhere" / "results").string() +
                          ", which does not exist"), std::string::npos) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << "solved first: " << o.output;
  EXPECT_FALSE(fs::exists(tmp.path() / "nowhere"));
}

TEST(WeakSpots, OverflowingLawConstantIsNamed) {
  TempDir tmp("overflow");
  const fs::path c = rectangle_case(tmp.path(), 1, 1, "[2, 2]",
                                    "[[dirichlet]]\nfaces = [\"left\"]\ncomponent = \"x\"\n"
                                    "[[dirichlet]]\nfaces = [\"bottom\"]\ncomponent = \"y\"\n"
                                    "[[pressure]]\nfaces = [\"top\"]\nvalue = 0.01\n",
                                    "model = \"mooney_rivlin\"\nC10 = 1e200\nC01 = 0.1\nbulk_modulus = 1.0\n");
  const Outcome o = run_igac("run " + quote(c.string()) + " --quiet --out out", tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("[material] C10: C10 = 1e+200 is outside [-1e100, 1e100]"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("E = "), std::string::npos) << "blamed on a key the user never set: " << o.output;
}

TEST(WeakSpots, SmallDeformationFarBeyondItsAssumptionsIsWarned) {
  TempDir tmp("far");
  // A unit square pressed onto a plane 99 units below: it moves 99 body sizes.
  const std::string loads = "[[dirichlet]]\nfaces = [\"left\"]\ncomponent = \"x\"\n"
                            "[[pressure]]\nfaces = [\"top\"]\nvalue = 0.01\n"
                            "[contact]\nface = \"bottom\"\n[contact.obstacle]\ntype = \"plane\"\n"
                            "point = [0.0, -99.0]\nnormal = [0.0, 1.0]\n";
  const fs::path c = rectangle_case(tmp.path(), 1, 1, "[4, 4]", loads);
  const Outcome o = run_igac("run " + quote(c.string()) + " --out out", tmp.path());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  const std::string says = "% of the body's size 1: far beyond small deformation";
  EXPECT_NE(o.output.find("igac: warning: "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("the largest displacement, 99, is 99"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find(says), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("[material] model a hyperelastic law (neo_hookean"), std::string::npos) << o.output;
  const nlohmann::json j = summary(tmp.path() / "out");
  ASSERT_TRUE(j.contains("warnings")) << j.dump();
  ASSERT_EQ(j["warnings"].size(), 1u);
  EXPECT_NE(j["warnings"][0].get<std::string>().find(says), std::string::npos);
  // The same square on a plane just below it: nothing to say.
  const fs::path near = rectangle_case(tmp.path(), 1, 1, "[4, 4]", loads.substr(0, loads.find("point")) +
                                       "point = [0.0, -0.001]\nnormal = [0.0, 1.0]\n");
  const Outcome quiet = run_igac("run " + quote(near.string()) + " --out near", tmp.path());
  EXPECT_EQ(quiet.exit_code, 0) << quiet.output;
  EXPECT_EQ(quiet.output.find("warning"), std::string::npos) << quiet.output;
  EXPECT_FALSE(summary(tmp.path() / "near").contains("warnings"));
}

TEST(WeakSpots, ThinHeldBodyInSmallUnitsIsHeld) {
  TempDir tmp("thin");
  // A wall 1e-7 long and 1e-10 thick (aspect 1000), clamped on its left end:
  // the rotation its clamp holds was taken for a free one (its lever, 1e-10,
  // below an absolute 1e-10 rank test).
  for (const std::string size : {"1e-07, 1e-10", "1000.0, 1.0"}) {
    const fs::path c = tmp.path() / "thin.toml";
    std::ofstream(c) << "name = \"thin\"\n[geometry]\nshape = \"rectangle\"\nsize = [" << size
                     << "]\n[mesh]\ndegree = 2\nelements = [64, 1]\n[material]\nE = 1.0\nnu = 0.3\n"
                        "[[dirichlet]]\nfaces = [\"left\"]\ncomponent = \"x\"\n"
                        "[[dirichlet]]\nfaces = [\"left\"]\ncomponent = \"y\"\n"
                        "[[pressure]]\nfaces = [\"top\"]\nvalue = 1e-15\n";
    const Outcome o = run_igac("run " + quote(c.string()) + " --quiet --out out", tmp.path());
    EXPECT_EQ(o.exit_code, 0) << size << ": " << o.output;
    EXPECT_EQ(o.output.find("not held"), std::string::npos) << size << ": " << o.output;
    EXPECT_EQ(summary(tmp.path() / "out").value("status", ""), "converged") << size;
  }
}

TEST(WeakSpots, LargeDeformationThatNothingLoadsConvergesToZero) {
  TempDir tmp("unloaded");
  // hertz2d_neohookean_pressure at zero pressure: held along y by the
  // contact only; Newton stopped in its line search (exit 1) after 12 s.
  std::string text = igac_test::read_file(std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d_neohookean_pressure.toml");
  const auto at = text.find("value = 0.1");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 11, "value = 0.0");
  std::ofstream(tmp.path() / "zero.toml") << text;
  const Outcome o = run_igac("run zero.toml --out out", tmp.path());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("igac: warning: "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("nothing loads the body"), std::string::npos) << o.output;
  const nlohmann::json j = summary(tmp.path() / "out");
  EXPECT_EQ(j.value("status", ""), "converged");
  EXPECT_EQ(j["contact"].value("total_force", 1.0), 0.0);
  ASSERT_TRUE(j.contains("warnings"));
  // The plane sliding along itself loads nothing either; moving away from a
  // body that only the contact holds, it leaves it not held.
  const auto normal = text.find("normal = [0.0, 1.0]");
  ASSERT_NE(normal, std::string::npos);
  for (const std::string motion : {"[0.1, 0.0]", "[0.0, -0.1]"}) {
    std::string moved = text;
    moved.insert(normal, "motion = " + motion + "\n");
    std::ofstream(tmp.path() / "moved.toml") << moved;
    const Outcome mo = run_igac("run moved.toml --quiet --out moved", tmp.path());
    if (motion == "[0.1, 0.0]") {
      EXPECT_EQ(mo.exit_code, 0) << mo.output;
      EXPECT_EQ(summary(tmp.path() / "moved").value("status", ""), "converged");
    } else {
      EXPECT_EQ(mo.exit_code, 2) << mo.output;
      EXPECT_NE(mo.output.find("the body is not held: 1 rigid motion(s) are free of Dirichlet conditions and only the "
                               "contact holds them, but nothing presses the body on the obstacle and the obstacle "
                               "moves away from it"), std::string::npos) << mo.output;
    }
  }
  // A free rigid motion says "not held", as the small-deformation path does.
  text.replace(text.find("[contact]"), std::string::npos, "");
  std::ofstream(tmp.path() / "free.toml") << text;
  const Outcome f = run_igac("run free.toml --out free", tmp.path());
  EXPECT_EQ(f.exit_code, 2) << f.output;
  EXPECT_NE(f.output.find("the body is not held"), std::string::npos) << f.output;
}

}  // namespace
