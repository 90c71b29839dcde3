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
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

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

}  // namespace
}  // namespace igac
