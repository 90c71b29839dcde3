// SPDX-License-Identifier: BSD-3-Clause
// A body force in large deformation (issue 36: it was accepted and ignored,
// "converged" with 0 Newton iterations and a zero reaction).  Dead, per unit
// reference volume: the supports carry its resultant, the Newton matrix has
// no term of it (checked against central differences), and at a small load
// the Neo-Hookean solution is the linear one to first order in the load.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "model/finite_strain_problem.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/central_differences.hpp"
#include "tests/support/igac_process.hpp"

using namespace igac;

namespace {

// A unit square of 4 x 4 elements held on its bottom face, under the body
// force `b` (a TOML vector), with the law `law`.
Model block(const std::filesystem::path& dir, const std::string& law, const std::string& b) {
  const std::filesystem::path file = dir / "block.toml";
  std::ofstream(file) << "name = \"block\"\n[geometry]\nshape = \"rectangle\"\nsize = [1.0, 1.0]\n"
                      << "[mesh]\ndegree = 2\nelements = [4, 4]\n[material]\nmodel = \"" << law
                      << "\"\nE = 1.0\nnu = 0.3\n[[dirichlet]]\nfaces = [\"bottom\"]\ncomponent = \"x\"\n"
                      << "[[dirichlet]]\nfaces = [\"bottom\"]\ncomponent = \"y\"\n[body_force]\nvalue = " << b << "\n";
  Model m = build_model(read_case(file.string()));
  return m;
}

TEST(BodyForceLargeDeformation, TheSupportsCarryItsResultant) {
  // The free rows' residual is at most the Newton tolerance times the force
  // scale; the reactions are the sum of the rest (the basis sums to one).
  constexpr double kNewton = 1e-8;
  igac_test::TempDir tmp("bodyforce");
  const Model m = block(tmp.path(), "neo_hookean", "[0.02, -0.1]");
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  ASSERT_TRUE(r.load_steps);
  int newton = 0;
  for (const auto& s : r.load_steps->steps) newton += s.newton_iterations;
  EXPECT_GT(newton, 0);
  ASSERT_EQ(r.dirichlet_reactions.size(), 1u);
  const Eigen::VectorXd& f = r.dirichlet_reactions[0].force;  // minus the weight of the unit square
  EXPECT_NEAR(f[0], -0.02, kNewton * 0.1);
  EXPECT_NEAR(f[1], 0.1, kNewton * 0.1);
  EXPECT_GT(r.u.col(1).cwiseAbs().maxCoeff(), 1e-3);  // it moved
}

TEST(BodyForceLargeDeformation, TangentMatchesCentralDifferences) {
  constexpr double kTolerance = 1e-6;  // relative to the column's largest entry
  igac_test::TempDir tmp("bodyforcefd");
  const Model m = block(tmp.path(), "neo_hookean", "[0.05, -0.2]");
  FiniteStrainProblem problem(finite_strain_setup(m));
  double t = 0;
  const Eigen::VectorXd x = igac_test::converged_state(problem, &t, 2);
  ASSERT_GT(x.cwiseAbs().maxCoeff(), 1e-2);  // a state well away from the reference
  std::vector<int> columns;
  for (int j = 0; j < problem.size(); j += 3) columns.push_back(j);
  EXPECT_EQ(igac_test::expect_jacobian_matches_central_differences(problem, t, x, columns, kTolerance),
            int(columns.size()));
}

// u_NH - u_lin is second order in the load: relative to u it falls by 10
// when the load does.
TEST(BodyForceLargeDeformation, SmallLoadLimitIsLinearElasticity) {
  igac_test::TempDir tmp("bodyforcelimit");
  double previous = 0;
  for (const std::string& b : {"[0.003, -0.01]", "[0.0003, -0.001]"}) {
    const Model nh = block(tmp.path(), "neo_hookean", b);
    const RunResult rn = solve_model(nh);
    const Model lin = block(tmp.path(), "linear_elastic", b);
    const RunResult rl = solve_model(lin);
    ASSERT_EQ(rn.status, "converged");
    const double relative = (rn.u - rl.u).cwiseAbs().maxCoeff() / rl.u.cwiseAbs().maxCoeff();
    std::printf("body force %s: |u_NH - u_lin| / |u_lin| = %.3g\n", b.c_str(), relative);
    EXPECT_LT(relative, 0.05);
    if (previous > 0) EXPECT_NEAR(previous / relative, 10.0, 1.0) << "first order in the load";
    previous = relative;
  }
}

}  // namespace
