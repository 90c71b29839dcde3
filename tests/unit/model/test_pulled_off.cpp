// SPDX-License-Identifier: BSD-3-Clause
// A contact that opens (issue 35, item 4).  A pair whose load reverses must
// open: where something else holds the body, every multiplier is released
// (lambda = 0, no contact force); where only the contact held it, the run
// fails and says that the load pulls the body off.  Before, a body held only
// by contact kept the multipliers nearest to the contact active whatever
// their sign (contact/small_strain_contact.cpp, next_active_set): two blocks
// pulled apart "converged" with a contact force of -0.01, a roller or a disc
// on a plane cycled, and large deformation ended in cut-backs and a Newton
// failure that named no cause.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "contact/small_strain_contact.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/igac_process.hpp"

namespace igac {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = IGAC_SOURCE_DIR;

// The text of `file` (from the source tree) with `line` inserted after the
// first line that starts with `after`, and `tail` appended; geometry files
// named whole.
std::string edited(const std::string& file, const std::string& after, const std::string& line,
                   const std::string& tail = "") {
  std::string text = igac_test::read_file(kSource / file);
  if (const auto at = text.find("file = \""); at != std::string::npos)
    text.insert(at + 8, (kSource / file).parent_path().string() + "/");
  const auto at = text.find("\n" + after);
  EXPECT_NE(at, std::string::npos) << after;
  if (at != std::string::npos && !line.empty()) text.insert(text.find('\n', at + 1) + 1, line + "\n");
  return text + "\n" + tail + "\n";
}

// `text` with `from` (which must occur) replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

RunResult solved(const std::string& text) {
  Model m = build_model(read_case_text(text, "pulled.toml"));
  return solve_model(m, quiet_run());
}

// The pressure of `file` along 0 -> 1 -> -1 (pushing, then pulling as hard).
const std::string kReversed = "curve = [[0, 0], [1, 1], [2, -1]]";

void expect_pulled_off(const RunResult& r, const std::string& stopped_at, const std::string& what) {
  EXPECT_EQ(r.status.text().rfind(stopped_at + ": the load pulls the body off the contact, and nothing else holds it (", 0), 0u)
      << what << ": " << r.status;
}

// Small deformation, along a load curve: each pair pushed, then pulled.
// The steps up to t = 1.5 (where the pressure is 0) converge; at t = 2 the
// load pulls the upper body off: the run stops there.
TEST(PulledOff, SmallDeformationPairsAndObstaclesFail) {
  const std::string steps = "[loading]\nsteps = 2";
  const RunResult blocks = solved(edited("cases/two_blocks.toml", "value = 0.01", kReversed, steps));
  expect_pulled_off(blocks, "stopped at time 2", "two blocks");
  ASSERT_EQ(blocks.load_curve.size(), 3u);  // t = 0.5, 1, 1.5
  EXPECT_NEAR(blocks.load_curve.back().contact_force(), 0.0, 1e-15);
  const std::string none = "solution = \"none\"";
  const RunResult plane =
      solved(replaced(edited("cases/hertz2d.toml", "value = 0.003", kReversed, steps), "solution = \"hertz\"", none));
  expect_pulled_off(plane, "stopped at time 2", "hertz2d");
  // 3D: the sphere octant on its plane, and on a block (coarse meshes)
  const RunResult octant = solved(
      replaced(edited("cases/hertz3d_study.toml", "value = 1e-4", kReversed, steps), "solution = \"hertz\"", none));
  expect_pulled_off(octant, "stopped at time 2", "hertz3d_study");
  std::string ball = edited("cases/sphere_on_block.toml", "value = 1e-4", kReversed, steps);
  ball = replaced(ball, "elements = [32, 8, 32]", "elements = [8, 2, 8]");
  ball = replaced(ball, "elements = [16, 16, 8]", "elements = [6, 6, 3]");
  expect_pulled_off(solved(ball), "stopped at time 2", "sphere on a block");
  // pulled from the first step on
  expect_pulled_off(solved(edited("cases/two_blocks.toml", "value = 0.01", "curve = [[0, 0], [1, -1]]", steps)),
                    "stopped at time 0.5", "two blocks pulled at once");
}

// The upper block lifted by its top face's prescribed displacement (down
// 0.01, then up 0.01): the pair opens and every multiplier is released; the
// same in large deformation.
TEST(PulledOff, PairHeldOtherwiseOpens) {
  std::string text = edited("cases/two_blocks.toml", "value = 0.01", "", "[loading]\nsteps = 2");
  const std::string pressure = "[[pressure]]\nfaces = [\"1:north\"]\nvalue = 0.01\n";
  ASSERT_NE(text.find(pressure), std::string::npos);
  text.replace(text.find(pressure), pressure.size(),
               "[[dirichlet]]\nfaces = [\"1:north\"]\ncomponent = \"y\"\nvalue = -0.01\n"
               "curve = [[0, 0], [1, 1], [2, -1]]\n");
  const RunResult r = solved(text);
  ASSERT_EQ(r.status, "converged");
  ASSERT_TRUE(r.contact);
  EXPECT_GT(r.load_curve.at(1).contact_force(), 0.0);  // pressed at t = 1
  EXPECT_EQ(r.contact->solution.lambda.norm(), 0.0);
  EXPECT_EQ(std::count(r.contact->solution.active.begin(), r.contact->solution.active.end(), 1), 0);
  EXPECT_EQ(r.contacts.at(0).report.total_force, 0.0);
  // Large deformation: the roller of finite_strain_two_bodies pressed down
  // 0.05 by its top face, then lifted 0.025 above where it started.
  std::string large = igac_test::read_file(kSource / "tests/data/finite_strain_two_bodies.toml");
  large = replaced(large, "[[pressure]]\nfaces = [\"roller:top\"]\nvalue = 0.05\n",
                   "[[dirichlet]]\nfaces = [\"roller:top\"]\ncomponent = \"y\"\nvalue = -0.05\n"
                   "curve = [[0, 0], [1, 1], [2, -0.5]]\n");
  const RunResult lifted = solved(large);
  ASSERT_EQ(lifted.status, "converged");
  ASSERT_GE(lifted.load_curve.size(), 3u);
  double pressed = 0;
  for (const LoadCurvePoint& p : lifted.load_curve) pressed = std::max(pressed, p.contact_force());
  EXPECT_GT(pressed, 0.0);
  EXPECT_EQ(lifted.load_curve.back().contact_force(), 0.0);
  EXPECT_EQ(lifted.contacts.at(0).report.total_force, 0.0);
}

// Large deformation, two bodies and an obstacle: the steps cut back until the
// increment is below min_increment (0.05 here, to keep the test short), and
// the status says why.
TEST(PulledOff, LargeDeformationSaysTheLoadPullsTheBodyOff) {
  const std::string fast = "min_increment = 0.05\nmax_newton_iterations = 12";
  const RunResult pair = solved(
      replaced(edited("tests/data/finite_strain_two_bodies.toml", "value = 0.05", kReversed), "steps = 4\n",
               "steps = 4\n" + fast + "\n"));
  EXPECT_NE(pair.status.text().find("the load pulls the body off the contact, and nothing else holds it"), std::string::npos)
      << pair.status;
  EXPECT_NE(pair.status.text().find("so at time 2, where the failed steps were going"), std::string::npos) << pair.status;
  const RunResult plane = solved(replaced(edited("cases/hertz2d_neohookean_pressure_study.toml", "value = 0.1", kReversed),
                                          "[loading]\n", "[loading]\n" + fast + "\n"));
  EXPECT_NE(plane.status.text().find("the load pulls the body off the contact, and nothing else holds it"), std::string::npos)
      << plane.status;
}

// The rule itself: a set held against the rule is counted, and a settled
// set that holds the body by such a multiplier is a failure, not converged.
TEST(PulledOff, SettledSetThatPullsIsNoSolution) {
  const Eigen::VectorXd lambda = Eigen::Vector3d(0.1, 0.0, 0.0), gap = Eigen::Vector3d(0.0, 0.2, 0.3);
  const std::vector<char> active = {1, 0, 0};
  int forced = -1;
  const std::vector<char> next = next_active_set(lambda, gap, active, 1, 1.0, &forced);
  EXPECT_EQ(next, active);  // the nearest to activation, kept to hold the body
  EXPECT_EQ(forced, 1);
  std::vector<char> current = active;
  std::set<std::vector<char>> seen;
  ContactSolution sol;
  EXPECT_TRUE(settle_active_set(next, current, seen, 0, sol, {}, forced));
  EXPECT_FALSE(sol.converged);
  EXPECT_EQ(sol.status, pulled_off_status(1));
  // pushing (lambda < 0): the rule keeps it, nothing forced, converged
  EXPECT_EQ(next_active_set(-lambda, gap, active, 1, 1.0, &forced), active);
  EXPECT_EQ(forced, 0);
  ContactSolution ok;
  EXPECT_TRUE(settle_active_set(active, current, seen, 0, ok, {}, forced));
  EXPECT_TRUE(ok.converged);
}

// load_pulls_off: the sign of the load's work along the free motion against
// the gaps' change.
TEST(PulledOff, LoadPullsOffWhenItsMotionOpensEveryGap) {
  const Eigen::VectorXd opens = Eigen::Vector3d(1.0, 0.5, 0.0);
  EXPECT_TRUE(load_pulls_off(opens, 1.0, 1.0));   // moves along +r: the gaps open or stay
  EXPECT_FALSE(load_pulls_off(opens, -1.0, 1.0));  // along -r: two close
  EXPECT_FALSE(load_pulls_off(Eigen::Vector3d(1.0, -0.5, 0.0), 1.0, 1.0));  // one closes: it can push back
  EXPECT_FALSE(load_pulls_off(opens, 1e-20, 1.0));  // no load along r (round-off)
}

}  // namespace
}  // namespace igac
