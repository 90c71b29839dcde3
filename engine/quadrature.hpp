// SPDX-License-Identifier: BSD-3-Clause
// Gauss-Legendre quadrature on [0, 1] (points by Newton iteration on the
// Legendre polynomial, Golub & Welsch give the same to round-off).  n points
// integrate polynomials of degree 2n-1 exactly; igac uses p+1 per direction.
#pragma once

#include <vector>

#include <Eigen/Dense>

namespace igac {

struct GaussRule {
  std::vector<double> points;   // in (0, 1)
  std::vector<double> weights;  // sum to 1
};

GaussRule gauss_legendre(int n);

// The tensor product of n-point Gauss rules on [0, 1]^d (d = 1, 2, 3), the
// first direction fastest.  Weights sum to 1.
struct TensorGaussRule {
  std::vector<Eigen::VectorXd> points;
  std::vector<double> weights;
};
TensorGaussRule tensor_gauss_rule(int param_dim, int n);

// A rule on the triangle {r, s >= 0, r + s <= 1}: the n x n Gauss rule of
// the square collapsed onto it (Duffy; Stroud's conical product), r = u,
// s = (1 - u) v, weight w_u w_v (1 - u) times 2.  Weights sum to 1 (times
// the triangle's area: the integral); exact for polynomials of total degree
// 2n - 2 (the collapse adds one degree in u).  Points as (r, s).
TensorGaussRule triangle_gauss_rule(int n);

}  // namespace igac
