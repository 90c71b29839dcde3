// SPDX-License-Identifier: BSD-3-Clause
// The rational tensor-product basis at one point, from the univariate
// B-spline (or Bernstein) values of each direction there (Piegl & Tiller,
// eq. 4.2 and 4.8; Cottrell, Hughes & Bazilevs, sec. 2.3):
//   B_a = w_a prod_d N^d_{a_d},   W = sum_a B_a,   R_a = B_a / W,
//   dR_a/dxi_d = (dB_a/dxi_d - R_a dW/dxi_d) / W,
// with dB_a/dxi_d the product with direction d's derivative in place of its
// value.  Local functions a = a_0 + np_0 (a_1 + np_1 a_2): first direction
// fastest, the numbering of PatchQuadrature, BezierMesh and NurbsPatch.
//
// This is the one kernel every basis evaluation of igac goes through (the
// quadrature of volumes and faces, the total-Lagrangian kernel, the follower
// pressure, point evaluation, Bezier cells).  The parametric dimension is a
// template parameter (2D and faces pay nothing for 3D); nothing allocates.
#pragma once

#include <array>

namespace igac {

// np[d] functions of direction d with values N[d][i] and derivatives
// dN[d][i] at the point; w[a] the weights.  Writes R[a] and, when dR is not
// null, dR[a * pd + d].  Returns W (the weight function at the point).
template <int pd>
double rational_basis_values(const int* np, const double* const* N, const double* const* dN, const double* w,
                             double* R, double* dR) {
  int nl = 1;
  for (int d = 0; d < pd; ++d) nl *= np[d];
  double W = 0;
  std::array<double, pd> dW{};
  for (int a = 0; a < nl; ++a) {
    std::array<int, pd> loc;
    for (int d = 0, r = a; d < pd; ++d) {
      loc[d] = r % np[d];
      r /= np[d];
    }
    double b = w[a];
    for (int d = 0; d < pd; ++d) b *= N[d][loc[d]];
    R[a] = b;
    W += b;
    if (!dR) continue;
    for (int d = 0; d < pd; ++d) {
      double g = w[a];
      for (int c = 0; c < pd; ++c) g *= c == d ? dN[c][loc[c]] : N[c][loc[c]];
      dR[a * pd + d] = g;
      dW[d] += g;
    }
  }
  const double iW = 1.0 / W;
  for (int a = 0; a < nl; ++a) {
    R[a] *= iW;
    if (dR)
      for (int d = 0; d < pd; ++d) dR[a * pd + d] = (dR[a * pd + d] - R[a] * dW[d]) * iW;
  }
  return W;
}

// The same with the parametric dimension (1, 2 or 3) known at run time.
inline double rational_basis_values(int pd, const int* np, const double* const* N, const double* const* dN,
                                    const double* w, double* R, double* dR) {
  switch (pd) {
    case 1: return rational_basis_values<1>(np, N, dN, w, R, dR);
    case 2: return rational_basis_values<2>(np, N, dN, w, R, dR);
    default: return rational_basis_values<3>(np, N, dN, w, R, dR);
  }
}

}  // namespace igac
