// SPDX-License-Identifier: BSD-3-Clause
// Nearly incompressible solids (engine/volumetric_projection.hpp), small
// deformation: the locking study on the thick cylinder under internal
// pressure (cases/lame_cylinder.toml, plane strain, closed form for any nu).
//  - mixed (B-bar, the volumetric strain projected per element): the
//    displacement error at nu = 0.49999 is within 2x of its error at
//    nu = 0.3 on the same mesh;
//  - displacement: the same ratio grows (locking); the factor is printed
//    (docs/benchmarks.md records it).
//  - At nu = 0.3 both converge to the closed form; the mixed one keeps the
//    optimal L2 rate p + 1 at nu = 0.49999.
//  - Large deformation: the same cylinder inflated by a follower pressure,
//    Neo-Hookean at K/mu = 5000, against the closed form of the
//    incompressible solid at a 55 % stretch of the bore (the bore alone does
//    not show locking: the displacement formulation's is as close, printed).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "engine/total_lagrangian.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

struct Errors {
  double l2, h1;
};

Errors lame_errors(double nu, Formulation f, int degree, int refine) {
  CaseSpec spec = read_case(IGAC_SOURCE_DIR "/cases/lame_cylinder.toml");
  spec.nu = nu;
  spec.material_parameters = {spec.E, nu, {}};
  spec.formulation = f;
  spec.write_vtk = false;
  apply_overrides(spec, degree, refine);
  const Model m = build_model(spec);
  const RunResult r = solve_model(m);
  EXPECT_EQ(r.status, "converged");
  if (!r.displacement_errors) {
    ADD_FAILURE() << "no errors against the closed form";
    return {INFINITY, INFINITY};
  }
  return {r.displacement_errors->l2 / r.displacement_errors->ref_l2, r.displacement_errors->h1 / r.displacement_errors->ref_h1};
}

TEST(NearlyIncompressible, LameMixedDoesNotLock) {
  for (int p : {2, 3}) {
    const Errors mixed_03 = lame_errors(0.3, Formulation::mixed, p, 2);
    const Errors mixed_05 = lame_errors(0.49999, Formulation::mixed, p, 2);
    const Errors disp_03 = lame_errors(0.3, Formulation::displacement, p, 2);
    const Errors disp_05 = lame_errors(0.49999, Formulation::displacement, p, 2);
    std::cout << "  Lame p = " << p << ": relative L2 error at nu = 0.3 / 0.49999: mixed " << mixed_03.l2 << " / "
              << mixed_05.l2 << " (x" << mixed_05.l2 / mixed_03.l2 << "), displacement " << disp_03.l2 << " / "
              << disp_05.l2 << " (x" << disp_05.l2 / disp_03.l2 << ")\n";
    EXPECT_LT(mixed_05.l2, 2 * mixed_03.l2) << "p = " << p;
    EXPECT_LT(mixed_05.h1, 2 * mixed_03.h1) << "p = " << p;
    EXPECT_GT(disp_05.l2, 5 * disp_03.l2) << "p = " << p << ": the displacement formulation locks";
  }
}

TEST(NearlyIncompressible, LameMixedConvergesAtOptimalRate) {
  const Errors coarse = lame_errors(0.49999, Formulation::mixed, 2, 2);
  const Errors fine = lame_errors(0.49999, Formulation::mixed, 2, 3);
  const double rate = std::log2(coarse.l2 / fine.l2);
  std::cout << "  Lame mixed p = 2, nu = 0.49999: L2 rate " << rate << "\n";
  EXPECT_GT(rate, 2.5);
}

// Incompressible Neo-Hookean (W = mu/2 (I1 - 3)) tube A <= R <= B in plane
// strain inflated to inner radius a: r^2 - a^2 = R^2 - A^2, b the outer
// radius, and radial equilibrium d sigma_rr/dr = mu (r^2/R^2 - R^2/r^2) / r
// integrated from a to b (sigma_rr(a) = -p, sigma_rr(b) = 0):
//   p = mu [ln(B/A) - ln(b/a) - (a^2 - A^2)/2 (1/b^2 - 1/a^2)].
double inflation_pressure(double a, double mu, double A, double B) {
  const double b = std::sqrt(a * a + B * B - A * A), c = a * a - A * A;
  return mu * (std::log(B / A) - std::log(b / a) - c / 2 * (1 / (b * b) - 1 / (a * a)));
}

// The bore of the inflated tube, from a case run: 1 + u_x at (A, 0).
// `incompressible`: K = infinity (the augmented Lagrangian); then
// *volume_change gets max_e |theta_e - 1| of the solution.
double inflated_bore(Formulation f, double pressure, bool incompressible = false, double* volume_change = nullptr) {
  CaseSpec spec = read_case(IGAC_SOURCE_DIR "/cases/lame_cylinder.toml");
  spec.model = "neo_hookean";
  const double nu = 0.4999, mu = 1.0;  // K / mu = 2 (1 + nu) / (3 (1 - 2 nu)) = 5000
  spec.E = 2 * mu * (1 + nu);
  spec.nu = nu;
  spec.material_parameters = {spec.E, nu, {}};
  spec.formulation = f;
  spec.write_vtk = false;
  spec.pressure.at(0).value = pressure;
  spec.loading.steps = 10;
  spec.reference = "none";
  spec.incompressible = incompressible;
  apply_overrides(spec, 2, 2);
  const Model m = build_model(spec);
  const RunResult r = solve_model(m);
  EXPECT_EQ(r.status, "converged") << formulation_name(f);
  if (volume_change) {
    const TotalLagrangianAssembler tl(m.body, *m.dofs, *m.law, f, false);
    Eigen::VectorXd dil;
    EXPECT_TRUE(tl.volume_changes(r.u, dil));
    *volume_change = dil.cwiseAbs().maxCoeff();
  }
  for (int i = 0; i < m.body.num_control_points(); ++i)
    if ((m.body.points().row(i) - Eigen::RowVector2d(1.0, 0.0)).norm() < 1e-12) return 1.0 + r.u(i, 0);
  ADD_FAILURE() << "no control point at (1, 0)";
  return NAN;
}

TEST(NearlyIncompressible, InflatedTubeMatchesTheIncompressibleClosedForm) {
  const double mu = 1.0, p = 0.45 * mu;
  double lo = 1.0, hi = 3.0;  // the closed form's bore at p (p(a) increases up to a ~ 3)
  for (int it = 0; it < 100; ++it) {
    const double mid = (lo + hi) / 2;
    (inflation_pressure(mid, mu, 1.0, 2.0) < p ? lo : hi) = mid;
  }
  const double a_exact = (lo + hi) / 2;
  const double a_mixed = inflated_bore(Formulation::mixed, p);
  const double a_disp = inflated_bore(Formulation::displacement, p);
  std::cout << "  inflated tube, p = " << p << " mu: bore a/A closed form " << a_exact << ", mixed " << a_mixed
            << ", displacement " << a_disp << "; error in a - A: mixed " << (a_mixed - a_exact) / (a_exact - 1)
            << ", displacement " << (a_disp - a_exact) / (a_exact - 1) << "\n";
  EXPECT_GT(a_exact, 1.5);
  EXPECT_NEAR(a_mixed - 1, a_exact - 1, 0.01 * (a_exact - 1));
}

// The incompressible limit (incompressible = true: K = infinity, the
// block pressures found by augmented-Lagrangian updates): every block's
// mean J is 1 to the run's tolerance 1e-8, and the bore matches the
// closed form of the incompressible solid at least as well as K/mu = 5000.
TEST(NearlyIncompressible, InflatedTubeInTheIncompressibleLimit) {
  const double mu = 1.0, p = 0.45 * mu;
  double lo = 1.0, hi = 3.0;
  for (int it = 0; it < 100; ++it) {
    const double mid = (lo + hi) / 2;
    (inflation_pressure(mid, mu, 1.0, 2.0) < p ? lo : hi) = mid;
  }
  const double a_exact = (lo + hi) / 2;
  double change_inc = NAN, change_k = NAN;
  const double a_inc = inflated_bore(Formulation::mixed, p, true, &change_inc);
  const double a_k = inflated_bore(Formulation::mixed, p, false, &change_k);
  std::cout << "  inflated tube, incompressible limit: bore error " << (a_inc - a_exact) / (a_exact - 1)
            << " (K/mu = 5000: " << (a_k - a_exact) / (a_exact - 1) << "), max |mean J - 1| " << change_inc
            << " (K/mu = 5000: " << change_k << ")\n";
  EXPECT_LE(change_inc, TotalLagrangianAssembler::kIncompressibilityTolerance);
  EXPECT_GT(change_k, 1e3 * TotalLagrangianAssembler::kIncompressibilityTolerance);  // K finite: J moves
  EXPECT_NEAR(a_inc - 1, a_exact - 1, 0.01 * (a_exact - 1));
  EXPECT_LE(std::abs(a_inc - a_exact), std::abs(a_k - a_exact) * 1.0001);
}

}  // namespace
}  // namespace igac
