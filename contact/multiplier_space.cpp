// SPDX-License-Identifier: BSD-3-Clause
#include "contact/multiplier_space.hpp"

#include <algorithm>
#include <fmt/format.h>

namespace igac {

MultiplierSpace::MultiplierSpace(const NurbsPatch& face) {
  for (int d = 0; d < face.param_dim(); ++d) {
    const KnotVector& kv = face.knots(d);
    const int p = kv.degree();
    if (p < 2)
      throw SplineError(fmt::format("contact needs displacement degree >= 2 (multipliers of degree p-2), got {}", p));
    const auto b = kv.breakpoints();
    const auto m = kv.multiplicities();
    std::vector<double> k(p - 1, b.front());
    for (size_t j = 1; j + 1 < b.size(); ++j) k.insert(k.end(), std::min(m[j], p - 1), b[j]);
    k.insert(k.end(), p - 1, b.back());
    knots_.emplace_back(p - 2, std::move(k));
    size_ *= knots_.back().num_basis();
  }
}

void MultiplierSpace::basis(const Eigen::VectorXd& xi, std::vector<int>& idx, std::vector<double>& val) const {
  const int fd = int(knots_.size());
  std::vector<std::vector<double>> b0, b1;
  const int s0 = knots_[0].find_span(xi[0]);
  knots_[0].basis_derivatives(s0, xi[0], 0, b0);
  const int q0 = knots_[0].degree();
  idx.clear();
  val.clear();
  if (fd == 1) {
    for (int j = 0; j <= q0; ++j) {
      idx.push_back(s0 - q0 + j);
      val.push_back(b0[0][j]);
    }
    return;
  }
  const int s1 = knots_[1].find_span(xi[1]);
  knots_[1].basis_derivatives(s1, xi[1], 0, b1);
  const int q1 = knots_[1].degree(), n0 = knots_[0].num_basis();
  for (int j1 = 0; j1 <= q1; ++j1)
    for (int j0 = 0; j0 <= q0; ++j0) {
      idx.push_back((s0 - q0 + j0) + n0 * (s1 - q1 + j1));
      val.push_back(b0[0][j0] * b1[0][j1]);
    }
}

Eigen::VectorXd MultiplierSpace::anchor(int K) const {
  Eigen::VectorXd x(knots_.size());
  for (size_t d = 0; d < knots_.size(); ++d) {
    const int n = knots_[d].num_basis();
    x[d] = knots_[d].greville()[K % n];
    K /= n;
  }
  return x;
}

}  // namespace igac
