// SPDX-License-Identifier: BSD-3-Clause
// A body held by contact alone (issue 37): the whole O-ring section, no
// Dirichlet condition, in a groove of four rigid planes (floor and cover
// squeezing it 25 %, side walls clear of it), with Coulomb friction 0.3
// and without.  Its rigid motions are pinned while the tangent is
// factorised and the amplitudes of those the contact holds are fixed by
// the equilibrium rows (docs/design.md, "Active set"); frictionless, the
// sliding along the planes is held by nothing and is left alone.  It
// converges as the quarter model with two symmetry planes
// (cases/oring_friction.toml) does, and the floor carries twice the
// quarter's force (the quarter is half the ring's width) to 1e-6 when both
// take the same load steps (with friction the answer depends on the path:
// 7 steps against 8 differ by 2e-4).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/two_d_models.hpp"

namespace igac {
namespace {

std::string plane(const std::string& friction, const std::string& point, const std::string& normal,
                  const std::string& motion = "") {
  return "[[contact]]\nface = \"arcs\"\nfriction = " + friction + "\n[contact.obstacle]\ntype = \"plane\"\npoint = " +
         point + "\nnormal = " + normal + "\n" + (motion.empty() ? "" : "motion = " + motion + "\n");
}

std::string floating_ring(const std::string& friction) {
  return "name = \"floating_ring\"\n[geometry]\nfile = \"" + std::string(IGAC_SOURCE_DIR) +
         "/cases/oring_full.xml\"\n"
         "[faces]\narcs = [\"0:south\", \"1:south\", \"2:south\", \"3:south\"]\n"
         "[mesh]\ndegree = 2\nelements = [8, 4]\n"
         "[material]\nmodel = \"mooney_rivlin\"\nC10 = 0.37\nC01 = 0.11\nbulk_modulus = 48.0\n"
         "[loading]\nsteps = 10\nmax_increment = 0.1\nmax_newton_iterations = 25\n" +
         plane(friction, "[0.0, -2.665]", "[0.0, 1.0]", "[0.0, 0.66625]") +   // the floor
         plane(friction, "[0.0, 2.665]", "[0.0, -1.0]", "[0.0, -0.66625]") +  // the cover
         plane(friction, "[-3.2, 0.0]", "[1.0, 0.0]") + plane(friction, "[3.2, 0.0]", "[-1.0, 0.0]") +
         "[output]\nvtk = false\n";
}

double floor_force(const std::string& text, const std::string& path) {
  const RunResult r = solve_model(build_model(read_case_text(text, path)), quiet_run());
  EXPECT_TRUE(r.status.is_converged()) << r.status.text();
  EXPECT_FALSE(r.reactions.empty());
  return r.reactions.empty() ? 0.0 : r.reactions.front().normal_force;
}

// The quarter model on the same mesh, ten fixed steps, with `friction`.
std::string quarter_ring(const std::string& friction) {
  std::string quarter = igac_test::shipped_case("oring_friction.toml");
  const auto replace = [&quarter](const std::string& from, const std::string& to) {
    quarter.replace(quarter.find(from), from.size(), to);
  };
  replace("elements = [32, 16]", "elements = [8, 4]");
  // Friction makes the answer depend on the load path: both take the same
  // ten steps.
  replace("steps = 20", "steps = 10\nmax_increment = 0.1");
  replace("friction = 0.3 ", "friction = " + friction + " ");
  return quarter;
}

void expect_twice_the_quarter(const std::string& friction) {
  const std::string dir = std::string(IGAC_SOURCE_DIR) + "/cases/";
  const double symmetric = floor_force(quarter_ring(friction), dir + "oring_friction.toml");
  const double floating = floor_force(floating_ring(friction), dir + "floating_ring.toml");
  std::printf("  friction %s, floor force: floating ring %.10g, twice the quarter %.10g\n", friction.c_str(), floating,
              2 * symmetric);
  EXPECT_NEAR(floating, 2 * symmetric, 1e-6 * floating);
}

TEST(FloatingBodies, ARingHeldByFrictionalContactAloneIsTheSymmetricModel) { expect_twice_the_quarter("0.3"); }

TEST(FloatingBodies, ARingHeldByFrictionlessContactAloneIsTheSymmetricModel) { expect_twice_the_quarter("0.0"); }

}  // namespace
}  // namespace igac
