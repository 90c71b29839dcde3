// SPDX-License-Identifier: BSD-3-Clause
// A body held by contact alone (issue 37): the whole O-ring section, no
// Dirichlet condition, in a groove of four rigid planes (floor and cover
// squeezing it 25 %, side walls clear of it), Coulomb friction 0.3.  Its
// rigid motions are pinned while the tangent is factorised and their
// amplitudes are fixed by the equilibrium rows (docs/design.md, "Active
// set"), so it converges as the quarter model with two symmetry planes
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

std::string plane(const std::string& point, const std::string& normal, const std::string& motion = "") {
  return "[[contact]]\nface = \"arcs\"\nfriction = 0.3\n[contact.obstacle]\ntype = \"plane\"\npoint = " + point +
         "\nnormal = " + normal + "\n" + (motion.empty() ? "" : "motion = " + motion + "\n");
}

std::string floating_ring() {
  return "name = \"floating_ring\"\n[geometry]\nfile = \"" + std::string(IGAC_SOURCE_DIR) +
         "/cases/oring_full.xml\"\n"
         "[faces]\narcs = [\"0:south\", \"1:south\", \"2:south\", \"3:south\"]\n"
         "[mesh]\ndegree = 2\nelements = [8, 4]\n"
         "[material]\nmodel = \"mooney_rivlin\"\nC10 = 0.37\nC01 = 0.11\nbulk_modulus = 48.0\n"
         "[loading]\nsteps = 10\nmax_increment = 0.1\nmax_newton_iterations = 25\n" +
         plane("[0.0, -2.665]", "[0.0, 1.0]", "[0.0, 0.66625]") +   // the floor
         plane("[0.0, 2.665]", "[0.0, -1.0]", "[0.0, -0.66625]") +  // the cover
         plane("[-3.2, 0.0]", "[1.0, 0.0]") + plane("[3.2, 0.0]", "[-1.0, 0.0]") + "[output]\nvtk = false\n";
}

double floor_force(const std::string& text, const std::string& path) {
  const RunResult r = solve_model(build_model(read_case_text(text, path)), quiet_run());
  EXPECT_TRUE(r.status.is_converged()) << r.status.text();
  EXPECT_FALSE(r.reactions.empty());
  return r.reactions.empty() ? 0.0 : r.reactions.front().normal_force;
}

TEST(FloatingBodies, ARingHeldByFrictionalContactAloneIsTheSymmetricModel) {
  std::string quarter = igac_test::shipped_case("oring_friction.toml");
  const std::string mesh = "elements = [32, 16]";
  quarter.replace(quarter.find(mesh), mesh.size(), "elements = [8, 4]");
  // Friction makes the answer depend on the load path: both take the same
  // ten steps.
  const std::string steps = "steps = 20";
  quarter.replace(quarter.find(steps), steps.size(), "steps = 10\nmax_increment = 0.1");
  const std::string dir = std::string(IGAC_SOURCE_DIR) + "/cases/";
  const double symmetric = floor_force(quarter, dir + "oring_friction.toml");
  const double floating = floor_force(floating_ring(), dir + "floating_ring.toml");
  std::printf("  floor force: floating ring %.10g, twice the quarter %.10g\n", floating, 2 * symmetric);
  EXPECT_NEAR(floating, 2 * symmetric, 1e-6 * floating);
}

}  // namespace
}  // namespace igac
