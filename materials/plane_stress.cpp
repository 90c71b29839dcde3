// SPDX-License-Identifier: BSD-3-Clause
#include "materials/plane_stress.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace igac {
namespace {

constexpr int kOut = 8;  // the index of F_33 in a 3D F flattened row by row

Eigen::Matrix3d embedded(const Eigen::Matrix2d& F, double s) {
  Eigen::Matrix3d F3 = Eigen::Matrix3d::Zero();
  F3.topLeftCorner<2, 2>() = F;
  F3(2, 2) = s;
  return F3;
}

// The root s of P_33(diag(F, s)) = 0 and the 3D P and A there; false when
// the law refuses a trial F or Newton does not converge.  Newton from the
// small-strain guess s0 = det(F)^-thinning (thinning = lambda / (lambda +
// 2 mu): eps_33 = -thinning tr eps to first order, and s = 1 / det F in the
// incompressible limit), each step at most halving or doubling s so it
// stays positive.  Once a step is below 1e-9 s the next would be at
// round-off (quadratic convergence): that step is taken to first order,
// P_iJ += A_iJ,33 step, and A kept (its error ~1e-9 relative), saving the
// evaluation a converged Newton spends on confirming itself.  For the
// linear law P_33 is affine in s: exact after the first step.
bool solve_stretch(const HyperelasticLaw& law, double thinning, const Eigen::Matrix2d& F, double& s, Eigen::Matrix3d& P,
                   Eigen::Matrix<double, 9, 9>& A) {
  if (!F.allFinite()) return false;
  const double det = F.determinant();
  s = det > 0 ? std::pow(det, -thinning) : 1.0;
  for (int it = 0; it < 60; ++it) {
    if (!law.evaluate(embedded(F, s), P, &A)) return false;
    const double slope = A(kOut, kOut);
    if (!(slope > 0)) return false;  // P_33 not increasing in s: no unique root
    const double step = std::clamp(-P(2, 2) / slope, -0.5 * s, s);
    s += step;
    if (std::abs(step) <= 1e-9 * s) {
      for (int i = 0; i < 3; ++i)
        for (int J = 0; J < 3; ++J) P(i, J) += A(3 * i + J, kOut) * step;
      return P.allFinite();
    }
  }
  return false;
}

}  // namespace

PlaneStressLaw::PlaneStressLaw(std::shared_ptr<const HyperelasticLaw> law) : law_(std::move(law)) {
  if (!law_) throw std::invalid_argument("PlaneStressLaw: no law");
  Eigen::Matrix3d P;
  Eigen::Matrix<double, 9, 9> A;
  if (law_->evaluate(Eigen::Matrix3d::Identity(), P, &A) && A(kOut, kOut) > 0) thinning_ = A(0, kOut) / A(kOut, kOut);
}

bool PlaneStressLaw::evaluate(const Eigen::Matrix2d& F, Eigen::Matrix2d& P, Eigen::Matrix4d* A) const {
  double s = 0;
  Eigen::Matrix3d P3;
  Eigen::Matrix<double, 9, 9> A3;
  if (!solve_stretch(*law_, thinning_, F, s, P3, A3)) return false;
  const Eigen::Matrix2d P_local = P3.topLeftCorner<2, 2>();
  if (A) {
    // The in-plane pairs iJ of the 3D layout, and the condensation on s.
    constexpr int in_plane[4] = {0, 1, 3, 4};
    Eigen::Matrix4d A_local;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        A_local(a, b) = A3(in_plane[a], in_plane[b]) - A3(in_plane[a], kOut) * A3(kOut, in_plane[b]) / A3(kOut, kOut);
    if (!A_local.allFinite()) return false;
    *A = A_local;
  }
  P = P_local;
  return true;
}

double PlaneStressLaw::energy(const Eigen::Matrix2d& F) const {
  double s = 0;
  Eigen::Matrix3d P3;
  Eigen::Matrix<double, 9, 9> A3;
  if (!solve_stretch(*law_, thinning_, F, s, P3, A3)) return std::numeric_limits<double>::infinity();
  return law_->energy(embedded(F, s));
}

double PlaneStressLaw::out_of_plane_stretch(const Eigen::Matrix2d& F) const {
  double s = 0;
  Eigen::Matrix3d P3;
  Eigen::Matrix<double, 9, 9> A3;
  return solve_stretch(*law_, thinning_, F, s, P3, A3) ? s : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace igac
