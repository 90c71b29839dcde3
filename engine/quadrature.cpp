// SPDX-License-Identifier: BSD-3-Clause
#include "engine/quadrature.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace igac {

GaussRule gauss_legendre(int n) {
  if (n < 1) throw std::invalid_argument("Gauss rule needs at least one point");
  GaussRule r;
  r.points.resize(n);
  r.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) p0 = 1;
      dp = n * (x * p1 - p0) / (x * x - 1);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    // recompute derivative at the converged point
    double p0 = 1, p1 = x;
    for (int k = 2; k <= n; ++k) {
      const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
      p0 = p1;
      p1 = p2;
    }
    dp = n * (x * p1 - p0) / (x * x - 1);
    r.points[n - 1 - i] = 0.5 * (x + 1);
    r.weights[n - 1 - i] = 1.0 / ((1 - x * x) * dp * dp);  // 2/((1-x^2)P'^2) scaled by 1/2
  }
  return r;
}

TensorGaussRule tensor_gauss_rule(int param_dim, int n) {
  const GaussRule g = gauss_legendre(n);
  TensorGaussRule r;
  const int n1 = n, n2 = param_dim > 1 ? n : 1, n3 = param_dim > 2 ? n : 1;
  for (int k = 0; k < n3; ++k)
    for (int j = 0; j < n2; ++j)
      for (int i = 0; i < n1; ++i) {
        Eigen::VectorXd s(param_dim);
        double w = g.weights[i];
        s[0] = g.points[i];
        if (param_dim > 1) s[1] = g.points[j], w *= g.weights[j];
        if (param_dim > 2) s[2] = g.points[k], w *= g.weights[k];
        r.points.push_back(s);
        r.weights.push_back(w);
      }
  return r;
}

TensorGaussRule triangle_gauss_rule(int n) {
  const GaussRule g = gauss_legendre(n);
  TensorGaussRule r;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = g.points[i];
      r.points.push_back(Eigen::Vector2d(u, (1 - u) * g.points[j]));
      r.weights.push_back(2 * g.weights[i] * g.weights[j] * (1 - u));
    }
  return r;
}

}  // namespace igac
