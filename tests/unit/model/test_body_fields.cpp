// SPDX-License-Identifier: BSD-3-Clause
// The ParaView body fields in one pass (recover_body_fields,
// model/field_recovery.hpp) against the separate recoveries they replace:
//  - one body in small deformation: the stress and strain are
//    recover_stress's with the case's law, J and the pressure
//    recover_volume's, to round-off;
//  - a mixed Neo-Hookean body in large deformation: the volume is
//    recover_volume's and the stress's volumetric part is the hydrostatic
//    pressure field's (-tr sigma / 3 = p at every Bezier point), while von
//    Mises is the law's (the pointwise recovery's);
//  - a law that throws in one element: the exception reaches the caller
//    (elements run in parallel; an exception must not end the process);
//  - free_cores (engine/free_cores.hpp) is between 1 and OpenMP's threads.
#include <gtest/gtest.h>

#include <omp.h>
#include <stdexcept>

#include "engine/free_cores.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/spline/refinement.hpp"
#include "io/case_file.hpp"
#include "model/field_recovery.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

// Round-off of a projection against the same projection done apart.
constexpr double kRoundOff = 1e-12;

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(b.cwiseAbs().maxCoeff(), 1e-300);
}

TEST(BodyFields, OnePassIsTheStressAndVolumeRecoveries) {
  CaseSpec spec = read_case(IGAC_SOURCE_DIR "/cases/hertz2d.toml");
  spec.elements = {16, 8};
  spec.write_vtk = false;
  const Model m = build_model(spec);
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  const BezierMesh mesh = body_bezier_mesh(m.body, r.u);
  const RecoveredFields all = recover_body_fields(mesh, m);
  const RecoveredStress stress = recover_stress(mesh, model_stress_law(m), false);
  const RecoveredVolume volume = recover_volume(mesh, m);
  EXPECT_LT(relative(all.stress.stress, stress.stress), kRoundOff);
  EXPECT_LT(relative(all.stress.strain, stress.strain), kRoundOff);
  EXPECT_LT(relative(all.stress.von_mises, stress.von_mises), kRoundOff);
  EXPECT_LT(relative(all.stress.principal, stress.principal), kRoundOff);
  EXPECT_LT(relative(all.volume.jacobian, volume.jacobian), kRoundOff);
  EXPECT_LT(relative(all.volume.pressure, volume.pressure), kRoundOff);
}

TEST(BodyFields, AMixedBodysStressCarriesTheFormulationsPressure) {
  CaseSpec spec = read_case(IGAC_SOURCE_DIR "/cases/cook_membrane.toml");
  spec.elements = {6, 6};
  spec.write_vtk = false;
  spec.model = "neo_hookean";
  spec.loading.steps = 2;
  const Model m = build_model(spec);
  ASSERT_EQ(m.patch_formulations().at(0), Formulation::mixed);
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  const BezierMesh mesh = body_bezier_mesh(m.body, r.u);
  const RecoveredFields all = recover_body_fields(mesh, m, r.element_pressures);
  const RecoveredVolume volume = recover_volume(mesh, m, r.element_pressures);
  EXPECT_LT(relative(all.volume.pressure, volume.pressure), kRoundOff);
  EXPECT_LT(relative(all.volume.jacobian, volume.jacobian), kRoundOff);
  const double scale = all.stress.stress.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  for (Eigen::Index i = 0; i < all.stress.stress.rows(); ++i)
    ASSERT_NEAR(-all.stress.stress.row(i).head(3).sum() / 3, all.volume.pressure[i], kRoundOff * scale) << "point " << i;
  const RecoveredStress law = recover_stress(mesh, model_stress_law(m), true);  // the pointwise law's stress
  EXPECT_LT(relative(all.stress.von_mises, law.von_mises), kRoundOff);         // no volumetric part
}

TEST(BodyFields, ALawThatThrowsInOneElementReachesTheCaller) {
  const NurbsPatch patch = subdivide(elevate_to(quarter_disc(1.0).patch, 2), 4);
  const BezierMesh mesh(patch, {Eigen::MatrixXd::Zero(patch.num_control_points(), 2)});
  int calls = 0;
  const StressLaw failing = [&](const Eigen::Matrix3d&) -> Eigen::Matrix3d {
#pragma omp atomic
    ++calls;
    throw std::runtime_error("this law fails");
  };
  EXPECT_THROW(recover_stress(mesh, failing), std::runtime_error);
  EXPECT_GT(calls, 0);
}

TEST(FreeCores, BetweenOneAndOpenMPsThreads) {
  const int n = free_cores();
  EXPECT_GE(n, 1);
  EXPECT_LE(n, std::max(1, omp_get_max_threads()));
}

}  // namespace
}  // namespace igac
