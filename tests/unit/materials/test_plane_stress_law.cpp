// SPDX-License-Identifier: BSD-3-Clause
// Plane stress made from any law (materials/plane_stress.hpp), for every
// registered law:
//  - sigma_zz = 0: the 3D law's P_33 at diag(F, s) vanishes at the stretch s
//    the wrapper solves, to round-off of the stiffness;
//  - P against central differences of the 2D energy and A (the in-plane
//    block condensed on s) against central differences of P (check_law);
//  - at F = I the small-deformation material is plane stress elasticity,
//    lambda* = 2 lambda mu / (lambda + 2 mu): E (1 + 2 nu) / (1 + nu)^2 and
//    nu / (1 + nu) as plane-strain constants;
//  - a non-finite F is refused with P and A untouched.
// Closed forms: the linear law's eps_zz = -nu / (1 - nu) (eps_xx + eps_yy);
// Neo-Hookean uniaxial stress, F = diag(l1, l2, l2) with P_22 = P_33 = 0.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>

#include "materials/plane_stress.hpp"

namespace igac {
namespace {

// As test_materials.cpp: check_law's differences are good to ~1e-9 of the
// stiffness on these F; a wrong condensation shows at 1e-2 .. 1.
constexpr double kFdTolerance = 1e-7;
constexpr double kRoundOff = 1e-12;

MaterialParameters parameters_of(const std::string& name, double E, double nu) {
  const MaterialParameters mp{E, nu};
  if (name != "mooney_rivlin") return mp;
  return {NAN, NAN, {{"C10", 0.35 * mp.mu()}, {"C01", 0.15 * mp.mu()}, {"bulk_modulus", mp.lambda() + 2 * mp.mu() / 3}}};
}

PlaneStressLaw plane_stress(const std::string& name, double E = 1.0, double nu = 0.3) {
  return PlaneStressLaw(std::shared_ptr<const HyperelasticLaw>(make_law(name, parameters_of(name, E, nu))));
}

// I, near it, and moderately far (entries perturbed by 0.25, J >= 0.6),
// where every registered law has one stretch with P_33 = 0.
std::vector<Eigen::Matrix2d> sample_F() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Matrix2d> out{Eigen::Matrix2d::Identity()};
  for (double amplitude : {1e-2, 1e-2, 0.25, 0.25, 0.25, 0.25})
    for (;;) {
      const Eigen::Matrix2d F = Eigen::Matrix2d::Identity() + amplitude * Eigen::Matrix2d::NullaryExpr([&] { return u(rng); });
      if (F.determinant() >= 0.6) {
        out.push_back(F);
        break;
      }
    }
  out.push_back((Eigen::Matrix2d() << 1.4, 0, 0, 1).finished());  // uniaxial stretch
  return out;
}

class PlaneStress : public ::testing::TestWithParam<std::string> {};

TEST_P(PlaneStress, OutOfPlaneStressVanishes) {
  const PlaneStressLaw law = plane_stress(GetParam());
  for (const Eigen::Matrix2d& F : sample_F()) {
    const double s = law.out_of_plane_stretch(F);
    ASSERT_TRUE(std::isfinite(s) && s > 0) << GetParam() << " at F =\n" << F;
    Eigen::Matrix3d F3 = Eigen::Matrix3d::Zero(), P3;
    F3.topLeftCorner<2, 2>() = F;
    F3(2, 2) = s;
    Eigen::Matrix<double, 9, 9> A3;
    ASSERT_TRUE(law.law().evaluate(F3, P3, &A3));
    EXPECT_LE(std::abs(P3(2, 2)), kRoundOff * A3.cwiseAbs().maxCoeff()) << GetParam();
    Eigen::Matrix2d P;
    ASSERT_TRUE(law.evaluate(F, P, nullptr));
    EXPECT_LE((P - P3.topLeftCorner<2, 2>()).cwiseAbs().maxCoeff(), kRoundOff * A3.cwiseAbs().maxCoeff());
  }
}

TEST_P(PlaneStress, StressAndTangentMatchFiniteDifferences) {
  for (const double nu : {0.3, 0.45}) {
    const PlaneStressLaw law = plane_stress(GetParam(), 1.0, nu);
    for (const Eigen::Matrix2d& F : sample_F()) {
      const TangentCheck c = check_law(law, F, kFdTolerance);
      EXPECT_TRUE(c.ok) << GetParam() << " nu = " << nu << ": " << c.report << "\nF =\n" << F;
    }
  }
}

TEST_P(PlaneStress, LinearisesToPlaneStressElasticity) {
  constexpr double E = 210e3, nu = 0.3;
  const LinearElastic m = small_strain_material(plane_stress(GetParam(), E, nu), 2);
  EXPECT_NEAR(m.E(), E * (1 + 2 * nu) / ((1 + nu) * (1 + nu)), 1e-10 * E) << GetParam();
  EXPECT_NEAR(m.nu(), nu / (1 + nu), 1e-10) << GetParam();
  // and the in-plane modulus of a uniaxial stress: sigma_xx / eps_xx = E
  const double lambda_star = m.lambda(), mu = m.mu();
  EXPECT_NEAR(4 * mu * (lambda_star + mu) / (lambda_star + 2 * mu), E, 1e-10 * E);
}

TEST_P(PlaneStress, RefusesNonFiniteF) {
  const PlaneStressLaw law = plane_stress(GetParam());
  Eigen::Matrix2d F = Eigen::Matrix2d::Identity(), P = Eigen::Matrix2d::Constant(42.0);
  Eigen::Matrix4d A = Eigen::Matrix4d::Constant(42.0);
  F(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(law.evaluate(F, P, &A));
  EXPECT_TRUE((P.array() == 42.0).all() && (A.array() == 42.0).all());
  EXPECT_EQ(law.energy(F), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(law.out_of_plane_stretch(F)));
}

INSTANTIATE_TEST_SUITE_P(EveryLaw, PlaneStress, ::testing::ValuesIn(law_names()));

TEST(PlaneStressClosedForm, LinearLawThinsByNuOverOneMinusNu) {
  constexpr double nu = 0.3;
  const PlaneStressLaw law = plane_stress("linear_elastic", 5.0, nu);
  const Eigen::Matrix2d F = (Eigen::Matrix2d() << 1.002, 0.0005, -0.001, 0.9993).finished();
  const double s = law.out_of_plane_stretch(F);
  EXPECT_NEAR(s - 1, -nu / (1 - nu) * (F(0, 0) - 1 + F(1, 1) - 1), 1e-15);
}

// Neo-Hookean uniaxial stress along x: l2 = l3 = l by symmetry, with
// P_22 = mu (l - 1/l) + lambda ln(l1 l^2) / l = 0, and
// P_11 = mu (l1 - 1/l1) + lambda ln(l1 l^2) / l1.
TEST(PlaneStressClosedForm, NeoHookeanUniaxialStress) {
  constexpr double E = 1.0, nu = 0.3, l1 = 1.5;
  const double mu = E / (2 * (1 + nu)), lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  double l = 1;
  for (int it = 0; it < 50; ++it) {
    const double r = mu * (l - 1 / l) + lambda * std::log(l1 * l * l) / l;
    const double dr = mu * (1 + 1 / (l * l)) + lambda * (2 - std::log(l1 * l * l)) / (l * l);
    l -= r / dr;
  }
  const double P11 = mu * (l1 - 1 / l1) + lambda * std::log(l1 * l * l) / l1;
  const PlaneStressLaw law = plane_stress("neo_hookean", E, nu);
  const Eigen::Matrix2d F = (Eigen::Matrix2d() << l1, 0, 0, l).finished();
  Eigen::Matrix2d P;
  ASSERT_TRUE(law.evaluate(F, P, nullptr));
  EXPECT_NEAR(P(0, 0), P11, 1e-14);
  EXPECT_NEAR(P(1, 1), 0.0, 1e-14);
  EXPECT_NEAR(law.out_of_plane_stretch(F), l, 1e-14);
  std::printf("  uniaxial stress l1 = %.2f: l2 = l3 = %.15f, P11 = %.15f\n", l1, l, P11);
}

}  // namespace
}  // namespace igac
