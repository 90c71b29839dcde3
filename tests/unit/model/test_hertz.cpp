// SPDX-License-Identifier: BSD-3-Clause
// The 2D Hertz benchmarks of the paper (Antolin, Buffa & Fabre 2018,
// section 4.1; docs/design.md, "Reference solutions"): cases/hertz2d.toml (P = 0.003) and
// cases/hertz2d_high_load.toml (P = 0.01), quarter disc of radius R = 1,
// E = 1, nu = 0.3, on a rigid plane.
//  - Analytic a and p0 (Johnson) equal the values printed in docs/design.md ("Reference solutions").
//  - The computed max pressure, half width and contact force against them.
//  - p = 3 (N3/S1): stable, no oscillation from one multiplier to the next.
//  - A p = 2 refinement study on nested meshes: the displacement H1 and L2
//    rates and the pressure rates against a refined reference and Hertz
//    (paper: ~1.5, ~2, ~0.8, ~0.6; measured here 2.02, 3.36, 1.38, 1.27).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "contact/pressure.hpp"
#include "engine/error_norms.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

const std::string kSourceDir = IGAC_SOURCE_DIR;

// docs/design.md prints a and p0 with 5 significant digits: they agree with the
// formulas to half a unit in the last printed digit.
double printed_tolerance(double v) { return 0.5 * std::pow(10.0, std::floor(std::log10(std::abs(v))) - 4); }

constexpr double kR = 1.0, kE = 1.0, kNu = 0.3;
// Bands at the default refinement (64 x 16 graded), from the values measured
// at a01e0b0 (tests/data/golden):
//  - peak |p_max - p0| / p0: -0.185 % (p = 2), -0.168 % (p = 3): 0.5 % (was
//    2 %), a margin of 2.7;
//  - half width |a_h - a| / a: -0.76 % (P = 0.003), -1.24 % (P = 0.01), but
//    a_h moves by whole spans of the contact edge, 3.7 % (P = 0.003) and
//    4.1 % (P = 0.01) of a on these gradings: 5 %, about one span;
//  - contact force against P R: -3.3e-16 and -6.7e-16, round-off of the
//    solve (the 3D cases: <= 1.8e-15): 1e-12 (was 1e-8), a margin of 500.
constexpr double kMaxPressureBand = 0.005;  // |p_max - p0| / p0
constexpr double kHalfWidthBand = 0.05;     // |a_h - a| / a: a_h is bracketed by element size
constexpr double kForceTolerance = 1e-12;   // contact force vs P R, relative (round-off of the solve)

struct CaseRun {
  Model model;
  RunResult result;
};

CaseRun run_case(const std::string& file, std::optional<int> degree = {}, std::optional<int> refine = {}) {
  CaseSpec spec = read_case(kSourceDir + "/cases/" + file);
  apply_overrides(spec, degree, refine);
  CaseRun run{build_model(spec), {}};
  run.result = solve_model(run.model);
  return run;
}

TEST(Hertz2D, AnalyticValuesMatchDesign) {
  const HertzSolution low = hertz_cylinder(kR, 0.003, kE, kNu);
  EXPECT_NEAR(low.a, 0.083378, printed_tolerance(0.083378));
  EXPECT_NEAR(low.p0, 0.045812, printed_tolerance(0.045812));
  EXPECT_NEAR(low.a, 0.083378, 1e-5 * 0.083378);
  EXPECT_NEAR(low.p0, 0.045812, 1e-5 * 0.045812);
  const HertzSolution high = hertz_cylinder(kR, 0.01, kE, kNu);
  EXPECT_NEAR(high.a, 0.15223, printed_tolerance(0.15223));
  EXPECT_NEAR(high.p0, 0.083641, printed_tolerance(0.083641));
  // p(r) = p0 sqrt(1 - r^2/a^2) and the force per unit length on the half
  // cylinder pi a p0 / 2 = 2 R P.
  EXPECT_DOUBLE_EQ(low.pressure(0), low.p0);
  EXPECT_EQ(low.pressure(1.01 * low.a), 0.0);
  EXPECT_NEAR(std::numbers::pi * low.a * low.p0 / 2, 2 * kR * 0.003, 1e-15);
  // 3D (the values of cases/hertz3d.toml and hertz3d_high_load.toml): the
  // printed formula of the paper omits pi; these include it.
  const HertzSolution s = hertz_sphere(kR, 1e-4, kE, kNu);
  EXPECT_NEAR(s.a, 0.059853, printed_tolerance(0.059853));
  EXPECT_NEAR(s.p0, 0.041872, printed_tolerance(0.041872));
  const HertzSolution s5 = hertz_sphere(kR, 5e-4, kE, kNu);
  EXPECT_NEAR(s5.a, 0.10235, printed_tolerance(0.10235));
  EXPECT_NEAR(s5.p0, 0.071600, printed_tolerance(0.071600));
}

TEST(Hertz2D, DefaultCaseMatchesHertz) {
  const CaseRun run = run_case("hertz2d.toml");
  const RunResult& r = run.result;
  ASSERT_EQ(r.status, "converged");
  ASSERT_TRUE(r.hertz);
  EXPECT_NEAR(r.hertz->a, 0.083378, printed_tolerance(0.083378));
  EXPECT_NEAR(r.hertz->p0, 0.045812, printed_tolerance(0.045812));
  const PressureReport& rep = r.contacts.front().report;
  EXPECT_NEAR(rep.max_pressure, 0.045812, kMaxPressureBand * 0.045812);
  EXPECT_NEAR(rep.half_width, 0.083378, kHalfWidthBand * 0.083378);
  EXPECT_NEAR(rep.total_force, 0.003 * kR, kForceTolerance * 0.003 * kR);
  EXPECT_NEAR(r.applied_force, 0.003 * kR, kForceTolerance * 0.003 * kR);
  // L2 pressure error against Hertz: 2.41 % measured; Hertz's half space is
  // not the quarter disc, so it cannot go to zero, but it must be small:
  // 3 % (was 5 %), a margin of 1.25.
  ASSERT_TRUE(r.pressure_error);
  const double rel = r.pressure_error->first / r.pressure_error->second;
  EXPECT_LT(rel, 0.03);
  RecordProperty("max_pressure", std::to_string(rep.max_pressure));
  RecordProperty("half_width", std::to_string(rep.half_width));
  RecordProperty("pressure_l2_rel", std::to_string(rel));
}

TEST(Hertz2D, HighLoadCaseConverges) {
  // P = 0.01: a = 0.15 R, beyond the half-space hypothesis: the peak sits
  // below Hertz, measured -0.582 % at a01e0b0; 1 % (was 1.5 %), a margin of
  // 1.7.
  constexpr double kBelowHertzBand = 0.01;
  const CaseRun run = run_case("hertz2d_high_load.toml");
  const RunResult& r = run.result;
  ASSERT_EQ(r.status, "converged");
  ASSERT_TRUE(r.hertz);
  EXPECT_NEAR(r.hertz->a, 0.15223, printed_tolerance(0.15223));
  EXPECT_NEAR(r.hertz->p0, 0.083641, printed_tolerance(0.083641));
  const PressureReport& rep = r.contacts.front().report;
  EXPECT_LE(rep.max_pressure, 0.083641) << "below Hertz";
  EXPECT_GE(rep.max_pressure, (1 - kBelowHertzBand) * 0.083641);
  EXPECT_NEAR(rep.half_width, 0.15223, kHalfWidthBand * 0.15223);
  EXPECT_NEAR(rep.total_force, 0.01 * kR, kForceTolerance * 0.01 * kR);
  RecordProperty("max_pressure", std::to_string(rep.max_pressure));
  RecordProperty("half_width", std::to_string(rep.half_width));
}

TEST(Hertz2D, CubicIsStableWithoutOscillation) {
  // N3/S1: continuous piecewise-linear multipliers.  An unstable pair would
  // show as a pressure alternating from one multiplier to the next (paper,
  // section 2 and Fig. 1); Hertz's pressure is smooth and decreasing in r.
  const CaseRun run = run_case("hertz2d.toml", 3);
  const RunResult& r = run.result;
  ASSERT_EQ(r.status, "converged");
  const HertzSolution h = *r.hertz;
  const PressureReport& rep = r.contacts.front().report;
  EXPECT_NEAR(rep.max_pressure, h.p0, kMaxPressureBand * h.p0);
  EXPECT_NEAR(rep.total_force, 0.003 * kR, kForceTolerance * 0.003 * kR);
  EXPECT_NEAR(rep.half_width, h.a, kHalfWidthBand * h.a);
  // Inside r < 0.8 a the multipliers (ordered along the face, r increasing
  // from the contact point) decrease monotonically, and their second
  // differences stay near Hertz's: |p''| dr^2 <= 4.7 p0 (dr/a)^2 ~ 0.007 p0
  // on this mesh.  An oscillation of 1 % of p0 would give second
  // differences of ~0.04 p0.
  constexpr double kSecondDifferenceBand = 0.02;  // relative to p0
  constexpr double kMonotoneSlack = 1e-10;        // relative to p0: round-off
  std::vector<double> p;
  for (const auto& s : rep.multipliers)
    if (s.r < 0.8 * h.a) p.push_back(s.pressure);
  ASSERT_GE(p.size(), 10u) << "the contact zone spans many multipliers";
  double worst_second = 0;
  for (size_t k = 0; k + 1 < p.size(); ++k) EXPECT_LE(p[k + 1] - p[k], kMonotoneSlack * h.p0) << "multiplier " << k;
  for (size_t k = 1; k + 1 < p.size(); ++k) worst_second = std::max(worst_second, std::abs(p[k + 1] - 2 * p[k] + p[k - 1]));
  EXPECT_LT(worst_second, kSecondDifferenceBand * h.p0);
  RecordProperty("max_pressure", std::to_string(rep.max_pressure));
  RecordProperty("max_second_difference_over_p0", std::to_string(worst_second / h.p0));
}

// cases/hertz3d_p3.toml: N3/S1 on a 6.6k-dof mesh whose fine zone is fitted
// to the contact zone (coarse spans growing geometrically) reaches the 5 %
// relative L2 pressure error that the paper's p = 2 mesh (hertz3d, 31.9k
// dofs) misses at 9.3 %; measured 4.6 %, a -0.4 %, p0 +1.0 %.
TEST(Hertz3D, CubicOnAFittedMeshReachesFivePercent) {
  const CaseRun run = run_case("hertz3d_p3.toml");
  const RunResult& r = run.result;
  ASSERT_EQ(r.status, "converged");
  ASSERT_TRUE(r.hertz && r.pressure_error);
  EXPECT_EQ(run.model.dofs->num_free(), 6613);
  const PressureReport& rep = r.contacts.front().report;
  // The contact force balances the load to round-off; the load is pi R^2 P / 4
  // up to the quadrature of the rational top face on 16 x 16 spans (7e-8).
  const double F = std::numbers::pi * kR * kR * 1e-4 / 4;
  EXPECT_NEAR(rep.total_force, r.applied_force, kForceTolerance * F);
  EXPECT_NEAR(r.applied_force, F, 1e-6 * F);
  EXPECT_NEAR(rep.max_pressure, r.hertz->p0, 0.02 * r.hertz->p0);
  EXPECT_NEAR(rep.half_width, r.hertz->a, 0.02 * r.hertz->a);
  EXPECT_LT(r.pressure_error->first / r.pressure_error->second, 0.05);
  RecordProperty("pressure_l2_rel", std::to_string(r.pressure_error->first / r.pressure_error->second));
}

// ------------------------------------------------------------ p = 2 study

struct StudyLevel {
  double h = 0;                  // largest element diameter
  int dofs = 0;
  ErrorNorms displacement;       // against the finest level
  double pressure_vs_reference = 0, pressure_vs_hertz = 0;
  double seconds = 0;
};

// hertz2d at refine 0 .. levels-1 on nested meshes, errors of every level
// but the last against the last (the reference).
std::vector<StudyLevel> hertz_study(CaseSpec spec, int levels) {
  std::vector<CaseRun> runs;
  for (int l = 0; l < levels; ++l) {
    apply_overrides(spec, {}, l);
    CaseRun run{build_model(spec), {}};
    run.result = solve_model(run.model);
    EXPECT_EQ(run.result.status, "converged") << "refine " << l;
    runs.push_back(std::move(run));
  }
  const CaseRun& ref = runs.back();
  const NurbsPatch& ref_patch = ref.model.body.patch(0);
  const ContactPressure& p_ref = *ref.result.contacts.front().pressure;
  std::vector<StudyLevel> out;
  for (int l = 0; l + 1 < levels; ++l) {
    const CaseRun& r = runs[l];
    StudyLevel s;
    s.h = r.model.mesh_size;
    s.dofs = r.model.dofs->num_free();
    s.seconds = r.result.timing.total;
    s.displacement = errors_against_reference(r.model.body.patch(0), r.result.u, ref_patch, ref.result.u,
                                              ref_patch.degree(0) + 1);
    s.pressure_vs_reference =
        r.result.contacts.front().pressure
            ->l2_error(*ref.model.contacts.front().face,
                       [&](int side, const Eigen::VectorXd& xi, const Eigen::VectorXd&) { return p_ref.pressure_at(side, xi); },
                       ref_patch.degree(0) + 2)
            .first;
    s.pressure_vs_hertz = r.result.pressure_error->first;
    out.push_back(s);
  }
  return out;
}

double rate(double e0, double e1, double h0, double h1) { return std::log(e0 / e1) / std::log(h0 / h1); }

TEST(Hertz2DStudy, QuadraticRatesStayAtTheirMeasuredValues) {
  // hertz2d (64 x 16, the paper's grading along the face and layers graded
  // toward it) at refine 0..3; refine 3 (133k dofs) is the reference, so
  // refine 0 and 1 have h_ref <= h/4 as the paper asks, and the rates are
  // taken between them.  Paper (section 4.1, P = 0.003): H1 ~ 1.5, L2 ~ 2,
  // pressure vs reference ~ 0.8, vs Hertz ~ 0.6.  Measured at a01e0b0: H1
  // 2.020, L2 3.364, pressure vs reference 1.377, vs Hertz 1.265
  // (pre-asymptotic on the graded layers; the paper's uniform layers gave
  // 1.59, 3.03, 1.05, 0.98).  The lower ends sit 0.1-0.16 below the measured
  // rates (was 1.3, 1.8, 0.7, 0.5, far below): a rate falls by 0.1 when the
  // finer level's error grows by 7 % against the coarser one's.  The upper
  // ends catch a reference that is not one (a rate far above the smoothness
  // of the contact solution, ~1.5 in H1).
  constexpr double kH1RateMin = 1.9, kL2RateMin = 3.2, kPressureRefRateMin = 1.25, kPressureHertzRateMin = 1.15;
  constexpr double kRateMax = 3.5;
  constexpr int kLevels = 4;
  const std::vector<StudyLevel> st = hertz_study(read_case(kSourceDir + "/cases/hertz2d.toml"), kLevels);
  ASSERT_EQ(st.size(), size_t(kLevels - 1));
  for (size_t l = 0; l < st.size(); ++l)
    std::printf("refine %zu: h %.4g, %d dofs, %.2f s; displacement L2 %.4e H1 %.4e; pressure vs reference %.4e, "
                "vs Hertz %.4e\n",
                l, st[l].h, st[l].dofs, st[l].seconds, st[l].displacement.l2, st[l].displacement.h1,
                st[l].pressure_vs_reference, st[l].pressure_vs_hertz);
  const StudyLevel &a = st[0], &b = st[1];
  EXPECT_NEAR(a.h / b.h, 2.0, 0.1) << "nested meshes halve h";
  const double h1 = rate(a.displacement.h1, b.displacement.h1, a.h, b.h);
  const double l2 = rate(a.displacement.l2, b.displacement.l2, a.h, b.h);
  const double pref = rate(a.pressure_vs_reference, b.pressure_vs_reference, a.h, b.h);
  const double phertz = rate(a.pressure_vs_hertz, b.pressure_vs_hertz, a.h, b.h);
  std::printf("rates refine 0 -> 1: H1 %.3f, L2 %.3f, pressure vs reference %.3f, vs Hertz %.3f\n", h1, l2, pref,
              phertz);
  RecordProperty("rate_displacement_h1", std::to_string(h1));
  RecordProperty("rate_displacement_l2", std::to_string(l2));
  RecordProperty("rate_pressure_vs_reference", std::to_string(pref));
  RecordProperty("rate_pressure_vs_hertz", std::to_string(phertz));
  EXPECT_GE(h1, kH1RateMin);
  EXPECT_LE(h1, kRateMax);
  EXPECT_GE(l2, kL2RateMin);
  EXPECT_LE(l2, kRateMax + 1);
  EXPECT_GE(pref, kPressureRefRateMin);
  EXPECT_LE(pref, kRateMax);
  EXPECT_GE(phertz, kPressureHertzRateMin);
  EXPECT_LE(phertz, kRateMax);
  // Errors decrease monotonically over all reported levels.
  for (size_t l = 1; l < st.size(); ++l) {
    EXPECT_LT(st[l].displacement.h1, st[l - 1].displacement.h1);
    EXPECT_LT(st[l].pressure_vs_reference, st[l - 1].pressure_vs_reference);
    EXPECT_LT(st[l].pressure_vs_hertz, st[l - 1].pressure_vs_hertz);
  }
}

}  // namespace
}  // namespace igac
