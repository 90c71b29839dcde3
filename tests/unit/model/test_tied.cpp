// SPDX-License-Identifier: BSD-3-Clause
// Tied (bonded) contact, `[contact] law = "tied"` (contact/laws/tied.cpp):
// two bodies glued along non-matching faces.  The patch test of
// cases/two_blocks.toml (a block on a block, 3 and 5 elements along the
// interface) pulled instead of pressed: a frictionless pair opens and the
// upper block, held by the contact alone, flies off; a tie carries the
// tension, and the two blocks deform as one block does, the uniform state
// of plane strain uniaxial tension, to the solve's round-off (mortar ties
// pass the patch test).  Pressed, the tie gives the frictionless result
// (the blocks expand sideways alike: nothing to hold), in both kinematics.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <fmt/format.h>

#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/igac_process.hpp"

namespace igac {
namespace {

namespace fs = std::filesystem;
const fs::path kCases = fs::path(IGAC_SOURCE_DIR) / "cases";

// The uniform state is exact in the discrete space; what is left is the
// direct solve's round-off on a well-conditioned problem of ~200 unknowns.
constexpr double kRoundOff = 1e-10;

// cases/two_blocks.toml with the pressure `value` on the upper block's top
// and `contact` appended to its [[contact]] table; `model` its law.
std::string two_blocks(double value, const std::string& contact, const std::string& model = "linear_elastic") {
  std::string text = igac_test::read_file(kCases / "two_blocks.toml");
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  };
  replace("file = \"two_blocks.xml\"", "file = \"" + (kCases / "two_blocks.xml").string() + "\"");
  replace("value = 0.01", fmt::format("value = {}", value));
  replace("model = \"linear_elastic\"", fmt::format("model = \"{}\"", model));
  return text + contact + "\n";
}

struct Solved {
  Model model;
  RunResult result;
};

Solved solved(const std::string& text) {
  Solved s{build_model(read_case_text(text, "tied.toml")), {}};
  s.result = solve_model(s.model, quiet_run());
  return s;
}

TEST(TiedContact, PulledTheTwoBlocksDeformAsOne) {
  constexpr double P = 0.01, E = 1.0, nu = 0.3;
  const Solved s = solved(two_blocks(-P, "law = \"tied\""));
  ASSERT_EQ(s.result.status, "converged");
  // Plane strain, sigma_yy = P, sigma_xx = 0 (the east sides free):
  // eps_yy = (1 - nu^2) P / E, eps_xx = -nu (1 + nu) P / E; u = eps X at
  // every control point (the geometry is affine).
  const double eps_yy = (1 - nu * nu) * P / E, eps_xx = -nu * (1 + nu) * P / E;
  const Eigen::MatrixXd& X = s.model.body.points();
  ASSERT_EQ(s.result.u.rows(), X.rows());
  for (int a = 0; a < X.rows(); ++a) {
    EXPECT_NEAR(s.result.u(a, 0), eps_xx * X(a, 0), kRoundOff) << "control point " << a;
    EXPECT_NEAR(s.result.u(a, 1), eps_yy * X(a, 1), kRoundOff) << "control point " << a;
  }
  // The tie pulls: every multiplier lambda_K = +P (the pressure -P), and
  // the whole load goes through it.
  const ContactSolution& c = s.result.contact->solution;
  for (int K = 0; K < c.lambda.size(); ++K) EXPECT_NEAR(c.lambda[K], P, kRoundOff * P) << K;
  for (int K = 0; K < c.lambda_t.size(); ++K) EXPECT_NEAR(c.lambda_t[K], 0.0, kRoundOff * P) << K;
  ASSERT_EQ(s.result.reactions.size(), 1u);
  EXPECT_NEAR(s.result.reactions[0].normal_force, -P, kRoundOff * P);
}

TEST(TiedContact, PulledAFrictionlessPairOpens) {
  // The frictionless pair of the same load: nothing holds the upper block,
  // which the solve says before it starts.
  try {
    solved(two_blocks(-0.01, ""));
    ADD_FAILURE() << "a frictionless pair pulled apart was solved";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the load pulls the body away from the obstacle"), std::string::npos)
        << e.what();
  }
}

TEST(TiedContact, PressedItIsTheFrictionlessPair) {
  for (const std::string model : {"linear_elastic", "neo_hookean"}) {
    const Solved tied = solved(two_blocks(0.01, "law = \"tied\"", model));
    const Solved free = solved(two_blocks(0.01, "", model));
    ASSERT_EQ(tied.result.status, "converged") << model;
    ASSERT_EQ(free.result.status, "converged") << model;
    // Large deformation: both are Newton solves to their tolerance (1e-9
    // relative, docs/design.md), which bounds their difference.
    const double tolerance = model == "linear_elastic" ? kRoundOff : 1e-7;
    EXPECT_LT((tied.result.u - free.result.u).cwiseAbs().maxCoeff(), tolerance * free.result.u.cwiseAbs().maxCoeff())
        << model;
  }
}

TEST(TiedContact, LargeDeformationPulledHoldsAndBalances) {
  // Neo-Hookean, pulled by 0.01 (1 % strain): the tie carries the load to
  // Newton's tolerance, and the small-load limit is the linear solution.
  constexpr double P = 0.01;
  const Solved large = solved(two_blocks(-P, "law = \"tied\"", "neo_hookean"));
  const Solved small = solved(two_blocks(-P, "law = \"tied\""));
  ASSERT_EQ(large.result.status, "converged");
  ASSERT_EQ(large.result.reactions.size(), 1u);
  // (the pressure follows the top face, which contracts sideways: the
  // load is P times its current length)
  EXPECT_NEAR(large.result.reactions[0].normal_force, -large.result.applied_force, 1e-6 * P);
  EXPECT_LT(large.result.applied_force, P);
  // Geometric and material nonlinearity at a strain of 1e-2: O(1e-2) relative.
  const double top = small.result.u.col(1).maxCoeff();
  EXPECT_NEAR(large.result.u.col(1).maxCoeff(), top, 3e-2 * top);
}

TEST(TiedContact, ItTakesNoCoefficientAndCoulombNeedsOne) {
  EXPECT_THROW(read_case_text(two_blocks(0.01, "law = \"tied\"\nfriction = 0.3"), "tied.toml"), InputError);
  EXPECT_THROW(read_case_text(two_blocks(0.01, "law = \"coulomb\""), "tied.toml"), InputError);
  try {
    read_case_text(two_blocks(0.01, "law = \"glued\""), "tied.toml");
    ADD_FAILURE() << "an unknown law was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("[contact] law: \"glued\" is not an interface law (one of: frictionless, "
                                         "coulomb, tied)"),
              std::string::npos)
        << e.what();
  }
}

// A tie runs on PETSc as friction does (SmallStrainFriction's iterations
// through the linear backend); the spline multigrid, which preconditions the
// frictionless solve only, is refused in one line.
TEST(TiedContact, ThePetscSolverTakesItWithoutTheSplineMultigrid) {
  CaseSpec spec = read_case_text(two_blocks(0.01, "law = \"tied\""), "tied.toml");
  spec.solver.type = SolverType::petsc;
  EXPECT_EQ(check_petsc_case(spec), "");
  spec.solver.preconditioner = Preconditioner::spline_multigrid;
  EXPECT_EQ(check_petsc_case(spec),
            "the spline multigrid needs the multipliers apart from the displacements, and the law \"tied\" of contact "
            "face '1:south' solves them in one block with the displacements; leave preconditioner at \"options\" "
            "(default MUMPS LU)");
}

}  // namespace
}  // namespace igac
