// SPDX-License-Identifier: BSD-3-Clause
// Cook's membrane, nearly incompressible (cases/cook_membrane.toml: plane
// strain, E = 250, nu = 0.4999, a shear load of 100 on the right edge): the
// vertical displacement of the top right corner (48, 60) on nested meshes.
//  - mixed (B-bar over the sub-grid pressure: degree p - 1 on every other
//    breakpoint): within 0.5 % of igac's limit 7.77 (docs/benchmarks.md) on
//    every mesh from 4 x 4 (the corner value comes from below; 4 x 4 is
//    0.27 % under), the last refinement changes it by less than 0.1 %, the
//    Aitken extrapolation of the last three meshes is 7.77 to 0.5 % and the
//    finest mesh is within 3 % of the literature's 7.7;
//  - displacement: on the same meshes it locks: below the mixed value on
//    every mesh, 47 % below on the coarsest (4 x 4).
// Also: the [[traction]] load it uses integrates to its resultant.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "engine/follower_pressure.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

double cook_tip(Formulation f, int elements) {
  CaseSpec spec = read_case(IGAC_SOURCE_DIR "/cases/cook_membrane.toml");
  spec.formulation = f;
  spec.elements = {elements, elements};
  spec.write_vtk = false;
  const Model m = build_model(spec);
  const RunResult r = solve_model(m);
  EXPECT_EQ(r.status, "converged");
  for (int i = 0; i < m.body.num_control_points(); ++i)
    if ((m.body.points().row(i) - Eigen::RowVector2d(48.0, 60.0)).norm() < 1e-9) return r.u(i, 1);
  ADD_FAILURE() << "no control point at (48, 60)";
  return NAN;
}

TEST(CookMembrane, MixedConvergesToTheReferenceAndDisplacementLocks) {
  const int meshes[] = {4, 8, 16, 32};
  double mixed[4], disp[4];
  for (int k = 0; k < 4; ++k) {
    mixed[k] = cook_tip(Formulation::mixed, meshes[k]);
    disp[k] = cook_tip(Formulation::displacement, meshes[k]);
    std::cout << "  Cook " << meshes[k] << " x " << meshes[k] << ": tip u_y mixed " << mixed[k] << ", displacement "
              << disp[k] << "\n";
  }
  // igac's own limit is 7.77 (p = 2 and 3 on meshes to 64 x 64 extrapolated, docs/benchmarks.md), 0.9 %
  // above the literature's round 7.7; every mesh is close to it already, and the last refinement
  // barely moves the corner
  constexpr double kLimit = 7.77;
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(mixed[k], kLimit, 0.005 * kLimit) << meshes[k];
  EXPECT_LT(std::abs(mixed[3] - mixed[2]), 1e-3 * kLimit);
  // Aitken's extrapolation of the last three meshes finds the limit too
  const double d1 = mixed[2] - mixed[1], d2 = mixed[3] - mixed[2];
  const double limit = mixed[3] - d2 * d2 / (d2 - d1);
  std::cout << "  Cook mixed p = 2: extrapolated " << limit << "\n";
  EXPECT_NEAR(limit, kLimit, 0.005 * kLimit);
  EXPECT_NEAR(mixed[3], 7.7, 0.03 * 7.7);
  // locking: the displacement formulation is below on every mesh, 47 % below on the coarsest
  for (int k = 0; k < 4; ++k) EXPECT_LT(disp[k], 0.98 * mixed[k]) << meshes[k];
  EXPECT_LT(disp[0], 0.6 * mixed[0]);
}

TEST(CookMembrane, TractionLoadSumsToItsResultant) {
  CaseSpec spec = read_case(IGAC_SOURCE_DIR "/cases/cook_membrane.toml");
  spec.write_vtk = false;
  const Model m = build_model(spec);
  const DofMap all(m.body, {});
  Eigen::VectorXd f = Eigen::VectorXd::Zero(all.num_free());
  add_traction_loads(m, all, {}, f);
  double fx = 0, fy = 0;
  for (int dof = 0; dof < all.num_dofs(); ++dof) (dof % 2 == 0 ? fx : fy) += f[all.equation(dof)];
  EXPECT_NEAR(fx, 0.0, 1e-12);
  EXPECT_NEAR(fy, 100.0, 1e-11);  // 6.25 x the edge's length 16
}

}  // namespace
}  // namespace igac
