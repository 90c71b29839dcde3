// SPDX-License-Identifier: BSD-3-Clause
// The ParaView fields of the shipped cases as a user opens them: every
// solution_XXXX.vtu of a run through the igac executable.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <nlohmann/json.hpp>

#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/igac_process.hpp"
#include "tests/support/vtu_file.hpp"

namespace {

namespace fs = std::filesystem;

// Where two bodies touch, the weighted gaps vanish and the pointwise gap is
// the discretisation's penetration: measured 2.2e-4 a on roller_on_block
// (TwoBodyNormalGapFollowsTheMaster prints it); 0.01 a.
constexpr double kPenetrationFraction = 0.01;

// A case of several [[body]] tables: each cell says its body (issue 25),
// the roller's first (index 0), the block's after it (1).
TEST(VtkOutput, EachCellSaysItsBody) {
  igac_test::TempDir tmp("bodies");
  const std::string roller = std::string(IGAC_SOURCE_DIR) + "/cases/roller_on_block.toml";
  const auto o = igac_test::run_igac("run " + igac_test::quote(roller) + " --quiet --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto grid = igac_test::read_vtu((tmp.path() / "out" / "solution_0001.vtu").string());
  vtkDataArray* body = grid->GetCellData()->GetArray("body");
  vtkDataArray* patch = grid->GetCellData()->GetArray("patch");
  ASSERT_NE(body, nullptr);
  ASSERT_NE(patch, nullptr);
  std::set<std::pair<double, double>> patch_body;
  for (vtkIdType e = 0; e < body->GetNumberOfTuples(); ++e) patch_body.insert({patch->GetComponent(e, 0), body->GetComponent(e, 0)});
  EXPECT_EQ(patch_body, (std::set<std::pair<double, double>>{{0, 0}, {1, 1}}));
}

// Issue 25's von Mises >= 0 and |sigma| >= 0 on every shipped case: checked
// on the golden runs (tests/cli/test_golden_cases.cpp), which run them all
// with their ParaView files, but for the one shipped without them
// (cattaneo_mindlin_cycle, [output] vtk = false for time): here with them,
// its 32 steps of friction along curves, the loop of a cycled load.
TEST(VtkOutput, ScalarsThatCannotBeNegativeAreNotOnTheCycledFrictionCase) {
  igac_test::TempDir tmp("cycle");
  std::string text = igac_test::read_file(std::string(IGAC_SOURCE_DIR) + "/cases/cattaneo_mindlin_cycle.toml");
  const auto at = text.find("vtk = false");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 11, "vtk = true");
  fs::copy_file(std::string(IGAC_SOURCE_DIR) + "/cases/half_disc.xml", tmp.path() / "half_disc.xml");
  std::ofstream(tmp.path() / "cycle.toml") << text;
  const auto o = igac_test::run_igac("run cycle.toml --quiet --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  int files = 0;
  EXPECT_GE(igac_test::min_over_steps(tmp.path() / "out", "von_mises", files), 0.0);
  EXPECT_GE(igac_test::min_over_steps(tmp.path() / "out", "stress_magnitude", files), 0.0);
  EXPECT_EQ(files, 33);  // step 0 and the 32 steps
}

// Step 0 of a run solved once whose contact does not change with the load
// is written after the solve from the solve's own contact operator (two
// bodies: not a second segmented set-up). Its weighted gaps are the
// undeformed ones: those of the operator assembled afresh at load 0, to
// round-off, on the roller pressed on a block (two bodies, small
// deformation).
TEST(VtkOutput, StepZeroFromTheSolvesOperatorHasTheUndeformedGaps) {
  igac_test::TempDir tmp("step_zero");
  const std::string toml = std::string(IGAC_SOURCE_DIR) + "/cases/roller_on_block.toml";
  const auto o = igac_test::run_igac("run " + igac_test::quote(toml) + " --quiet --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const igac::Model m = igac::build_model(igac::read_case(toml));
  const igac::WeightedGapOperator fresh = igac::assemble_contact_operator(m, 0.0);
  const auto grid = igac_test::read_vtu((tmp.path() / "out" / "multipliers_0000.vtu").string());
  vtkDataArray* gap = grid->GetPointData()->GetArray("weighted_gap");
  vtkDataArray* lambda = grid->GetPointData()->GetArray("lambda");
  ASSERT_NE(gap, nullptr);
  ASSERT_NE(lambda, nullptr);
  ASSERT_EQ(gap->GetNumberOfTuples(), fresh.weights.size());
  const Eigen::VectorXd expected = fresh.g0.cwiseQuotient(fresh.weights);
  for (vtkIdType k = 0; k < gap->GetNumberOfTuples(); ++k) {
    EXPECT_NEAR(gap->GetComponent(k, 0), expected[k], 1e-12 * (1 + std::abs(expected[k]))) << k;
    EXPECT_EQ(lambda->GetComponent(k, 0), 0.0) << k;
  }
}

// The fields an engineer looks for (issue 25), on the two-patch Hertz case
// against a plane: step 0 is the undeformed body at time 0; the body has
// strain, principal stresses and the patch id; the contact part the
// traction p n (n the plane's normal: exactly the pressure's coefficients
// times n) and the normal gap, a length.
TEST(VtkOutput, FieldsAnEngineerLooksFor) {
  igac_test::TempDir tmp("fields");
  const std::string toml = std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d_two_patches.toml";
  const auto o = igac_test::run_igac("run " + igac_test::quote(toml) + " --quiet --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const fs::path out = tmp.path() / "out";
  const std::string pvd = igac_test::read_file(out / "solution.pvd");
  EXPECT_NE(pvd.find("<DataSet timestep=\"0\" part=\"0\" name=\"body\" file=\"solution_0000.vtu\"/>"),
            std::string::npos) << pvd;
  EXPECT_NE(pvd.find("timestep=\"1\" part=\"1\" name=\"contact_face\" file=\"contact_0001.vtu\""), std::string::npos)
      << pvd;
  // step 0 has the contact parts too: no pressure, the initial gap
  EXPECT_NE(pvd.find("timestep=\"0\" part=\"1\" name=\"contact_face\" file=\"contact_0000.vtu\""), std::string::npos)
      << pvd;
  const auto contact0 = igac_test::read_vtu((out / "contact_0000.vtu").string());
  vtkDataArray* p0 = contact0->GetPointData()->GetArray("pressure");
  vtkDataArray* gap0 = contact0->GetPointData()->GetArray("normal_gap");
  ASSERT_NE(p0, nullptr);
  ASSERT_NE(gap0, nullptr);
  double gap_max = 0;
  for (vtkIdType i = 0; i < p0->GetNumberOfTuples(); ++i) {
    EXPECT_EQ(p0->GetComponent(i, 0), 0.0);
    EXPECT_GE(gap0->GetComponent(i, 0), -1e-12);  // the disc touches the plane at one point
    gap_max = std::max(gap_max, gap0->GetComponent(i, 0));
  }
  EXPECT_GT(gap_max, 0.1);  // the quarter disc's far end stands off the plane
  const auto undeformed = igac_test::read_vtu((out / "solution_0000.vtu").string());
  for (const char* a : {"displacement", "stress", "von_mises"}) {
    vtkDataArray* arr = undeformed->GetPointData()->GetArray(a);
    ASSERT_NE(arr, nullptr) << a;
    for (vtkIdType i = 0; i < arr->GetNumberOfValues(); ++i)
      ASSERT_EQ(arr->GetComponent(i / arr->GetNumberOfComponents(), int(i % arr->GetNumberOfComponents())), 0.0) << a;
  }

  const auto body = igac_test::read_vtu((out / "solution_0001.vtu").string());
  vtkDataArray* strain = body->GetPointData()->GetArray("strain");
  vtkDataArray* principal = body->GetPointData()->GetArray("principal_stress");
  vtkDataArray* patch = body->GetCellData()->GetArray("patch");
  ASSERT_NE(strain, nullptr);
  ASSERT_NE(principal, nullptr);
  ASSERT_NE(patch, nullptr);
  ASSERT_NE(body->GetPointData()->GetArray("patch"), nullptr);
  EXPECT_EQ(strain->GetNumberOfComponents(), 6);
  ASSERT_EQ(principal->GetNumberOfComponents(), 3);
  double strain_max = 0;
  for (vtkIdType i = 0; i < strain->GetNumberOfTuples(); ++i) {
    for (int c = 0; c < 6; ++c) strain_max = std::max(strain_max, std::abs(strain->GetComponent(i, c)));
    EXPECT_EQ(strain->GetComponent(i, 2), 0.0);  // plane strain
    EXPECT_GE(principal->GetComponent(i, 0), principal->GetComponent(i, 1));
    EXPECT_GE(principal->GetComponent(i, 1), principal->GetComponent(i, 2));
  }
  EXPECT_GT(strain_max, 0.0);
  std::set<double> patches;
  for (vtkIdType e = 0; e < patch->GetNumberOfTuples(); ++e) patches.insert(patch->GetComponent(e, 0));
  EXPECT_EQ(patches, (std::set<double>{0.0, 1.0}));

  const auto contact = igac_test::read_vtu((out / "contact_0001.vtu").string());
  vtkDataArray* p = contact->GetPointData()->GetArray("pressure");
  vtkDataArray* t = contact->GetPointData()->GetArray("traction");
  vtkDataArray* gap = contact->GetPointData()->GetArray("normal_gap");
  ASSERT_NE(t, nullptr);
  ASSERT_NE(gap, nullptr);
  ASSERT_NE(contact->GetCellData()->GetArray("normal_gap"), nullptr);
  double p_max = 0;
  for (vtkIdType i = 0; i < p->GetNumberOfTuples(); ++i) p_max = std::max(p_max, std::abs(p->GetComponent(i, 0)));
  ASSERT_GT(p_max, 0.0);
  for (vtkIdType i = 0; i < t->GetNumberOfTuples(); ++i) {
    EXPECT_NEAR(t->GetComponent(i, 0), 0.0, 1e-12 * p_max);                     // the plane y = const pushes along y
    EXPECT_NEAR(t->GetComponent(i, 1), p->GetComponent(i, 0), 1e-12 * p_max);  // n = (0, 1): t = p n
    EXPECT_GT(gap->GetComponent(i, 0), -1e-3);  // a length: the face is not inside the plane
  }
  ASSERT_NE(igac_test::read_vtu((out / "multipliers_0001.vtu").string())->GetPointData()->GetArray("normal_gap"), nullptr);
}

// A mixed run's stress fields take their volumetric part from the
// formulation's pressure, not from the pointwise law's K (J - 1), which
// oscillates at the scale the mixed pressure removes (issue 35: on the
// rubber O-ring -tr(sigma)/3 spanned -227 to +183 MPa where the pressure
// spans -0.10 to 1.16).  At every point of every step: -tr(sigma)/3 is the
// hydrostatic_pressure field, and the principal stresses sum to tr(sigma).
TEST(VtkOutput, MixedStressCarriesTheFormulationsPressure) {
  // Both sides are the same Bezier coefficients up to the round-off of
  // adding a shift to stresses of this size.
  constexpr double kRoundOff = 1e-12;
  igac_test::TempDir tmp("mixed");
  const std::string toml = std::string(IGAC_SOURCE_DIR) + "/cases/oring_rubber.toml";
  const auto o = igac_test::run_igac("run " + igac_test::quote(toml) + " --quiet --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  int files = 0;
  for (const auto& entry : fs::directory_iterator(tmp.path() / "out")) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with("solution_") || entry.path().extension() != ".vtu") continue;
    ++files;
    const auto body = igac_test::read_vtu(entry.path().string());
    vtkDataArray* stress = body->GetPointData()->GetArray("stress");
    vtkDataArray* principal = body->GetPointData()->GetArray("principal_stress");
    vtkDataArray* p = body->GetPointData()->GetArray("hydrostatic_pressure");
    ASSERT_TRUE(stress && principal && p) << name;
    double scale = 0, p_max = 0;
    for (vtkIdType i = 0; i < stress->GetNumberOfTuples(); ++i) {
      for (int c = 0; c < 6; ++c) scale = std::max(scale, std::abs(stress->GetComponent(i, c)));
      p_max = std::max(p_max, std::abs(p->GetComponent(i, 0)));
    }
    for (vtkIdType i = 0; i < stress->GetNumberOfTuples(); ++i) {
      const double trace = stress->GetComponent(i, 0) + stress->GetComponent(i, 1) + stress->GetComponent(i, 2);
      ASSERT_NEAR(-trace / 3, p->GetComponent(i, 0), kRoundOff * scale) << name << " point " << i;
      ASSERT_NEAR(principal->GetComponent(i, 0) + principal->GetComponent(i, 1) + principal->GetComponent(i, 2), trace,
                  kRoundOff * scale)
          << name << " point " << i;
    }
    if (name != "solution_0000.vtu") EXPECT_GT(p_max, 0.0) << name;
  }
  EXPECT_GT(files, 1);
}

// The normal gap is the distance to the partner, a length: in the
// multipliers' file at each multiplier's anchor (it was (Pi g)_K / K_K,
// 1.517 on hertz2d where the gap is 4.44e-3), g_n = Y + u_y + R against
// hertz2d's plane y = -R.
TEST(VtkOutput, MultiplierNormalGapIsTheDistanceToThePlane) {
  constexpr double kRoundOff = 1e-12;  // of the radius: the same sum, another order
  igac_test::TempDir tmp("mgap");
  const std::string toml = std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml";
  const auto o = igac_test::run_igac("run " + igac_test::quote(toml) + " --quiet --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto g = igac_test::read_vtu((tmp.path() / "out" / "multipliers_0001.vtu").string());
  vtkDataArray* gap = g->GetPointData()->GetArray("normal_gap");
  vtkDataArray* u = g->GetPointData()->GetArray("displacement");
  vtkDataArray* active = g->GetPointData()->GetArray("active");
  ASSERT_TRUE(gap && u && active);
  ASSERT_GT(g->GetNumberOfPoints(), 10);
  double far = 0;
  for (vtkIdType K = 0; K < g->GetNumberOfPoints(); ++K) {
    double X[3];
    g->GetPoint(K, X);
    const double expected = X[1] + u->GetComponent(K, 1) + 1.0;
    EXPECT_NEAR(gap->GetComponent(K, 0), expected, kRoundOff) << "multiplier " << K;
    far = std::max(far, gap->GetComponent(K, 0));
  }
  EXPECT_GT(far, 0.1);  // the quarter disc's far end stands off the plane
}

// Between two bodies the normal gap measures to the master where it stands
// now (it took the master at its reference position: -6.3e-4 in a closed
// shrink fit, +0.0044 in the loaded zone of a roller between plates): over
// the active zone of the roller on its block it is the discretisation's
// penetration, far below the zone's size; outside it positive.
TEST(VtkOutput, TwoBodyNormalGapFollowsTheMaster) {
  igac_test::TempDir tmp("bgap");
  const std::string toml = std::string(IGAC_SOURCE_DIR) + "/cases/roller_on_block.toml";
  const auto o = igac_test::run_igac("run " + igac_test::quote(toml) + " --quiet --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto summary = nlohmann::json::parse(igac_test::read_file(tmp.path() / "out" / "summary.json"));
  const double a = summary["contact"]["half_width"];
  const auto c = igac_test::read_vtu((tmp.path() / "out" / "contact_0001.vtu").string());
  vtkDataArray* gap = c->GetCellData()->GetArray("normal_gap");
  vtkDataArray* active = c->GetCellData()->GetArray("active");
  ASSERT_TRUE(gap && active);
  double closed = 0, open_min = std::numeric_limits<double>::infinity();
  int n_active = 0;
  for (vtkIdType e = 0; e < gap->GetNumberOfTuples(); ++e) {
    if (active->GetComponent(e, 0) > 0) {
      closed = std::max(closed, std::abs(gap->GetComponent(e, 0)));
      ++n_active;
    } else {
      open_min = std::min(open_min, gap->GetComponent(e, 0));
    }
  }
  ASSERT_GT(n_active, 3);
  std::printf("roller on block: |normal gap| <= %.3g over the active cells (a = %.4g), >= %.3g elsewhere\n", closed, a,
              open_min);
  EXPECT_LT(closed, kPenetrationFraction * a);
  EXPECT_GT(open_min, -kPenetrationFraction * a);
}

}  // namespace
