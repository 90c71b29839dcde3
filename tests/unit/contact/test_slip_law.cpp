// SPDX-License-Identifier: BSD-3-Clause
// The linearised Coulomb slip law of the 3D frictional solve
// (contact/small_strain_friction.hpp, linearise_slip): its derivatives in
// lambda_t, s and the bound b against central finite differences of
// Phi = lambda_t - b xi / |xi|, xi = lambda_t + c_t s, at slipping states
// (|xi| > b) in 2D and 3D tangent planes; and the row the solve builds from
// it, w . s = slip_compliance(alpha, c_t) w . lambda_t, is Phi's component
// across the slip direction.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "contact/small_strain_friction.hpp"

namespace igac {
namespace {

// Central differences with step kStep have an error of order kStep^2 times
// Phi's third derivatives (|xi| ~ 1 here): kTolerance is far above it and far
// below any wrong term (O(1)).
constexpr double kStep = 1e-6, kTolerance = 1e-7;

Eigen::VectorXd phi(const Eigen::VectorXd& lt, const Eigen::VectorXd& s, double b, double ct) {
  const Eigen::VectorXd xi = lt + ct * s;
  return lt - b * xi / xi.norm();
}

void check(const Eigen::VectorXd& lt, const Eigen::VectorXd& s, double b, double ct) {
  const SlipLinearisation lin = linearise_slip(lt, s, b, ct);
  const int n = int(lt.size());
  for (int j = 0; j < n; ++j) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(n, j) * kStep;
    const Eigen::VectorXd d_lt = (phi(lt + e, s, b, ct) - phi(lt - e, s, b, ct)) / (2 * kStep);
    const Eigen::VectorXd d_s = (phi(lt, s + e, b, ct) - phi(lt, s - e, b, ct)) / (2 * kStep);
    EXPECT_LE((d_lt - lin.d_lambda_t.col(j)).norm(), kTolerance) << "d/dlambda_t column " << j;
    EXPECT_LE((d_s - lin.d_s.col(j)).norm(), kTolerance) << "d/ds column " << j;
  }
  const Eigen::VectorXd d_b = (phi(lt, s, b + kStep, ct) - phi(lt, s, b - kStep, ct)) / (2 * kStep);
  EXPECT_LE((d_b - lin.d_b).norm(), kTolerance);
}

TEST(SlipLaw, LinearisationMatchesFiniteDifferences) {
  check(Eigen::Vector2d(0.3, -0.2), Eigen::Vector2d(0.5, 0.4), 0.25, 1.7);   // a disc, the slip turning the traction
  check(Eigen::Vector2d(-0.1, 0.05), Eigen::Vector2d(-0.2, 0.9), 0.6, 0.8);  // across the traction
  check((Eigen::VectorXd(1) << 0.2).finished(), (Eigen::VectorXd(1) << 0.3).finished(), 0.25, 2.0);  // 2D
}

// At a solution on the cone (lambda_t = b v, s = a v) Phi = 0; perturbing
// across v, the linearised law's component across v is the solve's row.
TEST(SlipLaw, CrossRowIsTheLawAcrossTheSlipDirection) {
  const Eigen::Vector2d v(0.6, 0.8), w(-0.8, 0.6);
  const double b = 0.3, ct = 2.0, a = 0.5;
  const Eigen::VectorXd lt = b * v, s = a * v;
  const SlipLinearisation lin = linearise_slip(lt, s, b, ct);
  EXPECT_LE(phi(lt, s, b, ct).norm(), 1e-15);
  const double alpha = b / (lt + ct * s).norm();
  // w . (dPhi/dlambda_t w) mu + w . (dPhi/ds w) sigma = 0  <=>  sigma = compliance * mu
  const double mu = 1.0, sigma = slip_compliance(alpha, ct) * mu;
  EXPECT_NEAR(w.dot(lin.d_lambda_t * w) * mu + w.dot(lin.d_s * w) * sigma, 0.0, 1e-14);
}

// In 3D c_t,K = E / h_K: E = c_n h, h_K = K_K^(1/2); in 2D or with no mesh size: c_n.
TEST(SlipLaw, TangentialScaleIsEOverTheMultipliersSize) {
  const Eigen::Vector2d w2(0.1, 0.05), w3(0.04, 0.01);
  const Eigen::VectorXd ct2 = tangential_scales(10.0, 0.2, w2, 2), ct3 = tangential_scales(5.0, 0.4, w3, 3),
                        none = tangential_scales(10.0, 0.0, w3, 3);
  EXPECT_EQ(ct2[0], 10.0);
  EXPECT_EQ(ct2[1], 10.0);
  EXPECT_NEAR(ct3[0], 10.0, 1e-12);  // E = 2, h_K = 0.2
  EXPECT_NEAR(ct3[1], 20.0, 1e-12);
  EXPECT_EQ(none[0], 10.0);
  EXPECT_EQ(none[1], 10.0);
}

}  // namespace
}  // namespace igac
