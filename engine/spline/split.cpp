// SPDX-License-Identifier: BSD-3-Clause
#include "engine/spline/split.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "engine/spline/refinement.hpp"

namespace igac {
namespace {

// A split value this close (relative to the range) to an existing knot is
// that knot: inserting a knot a round-off away would create a sliver span.
constexpr double kSnapTolerance = 1e-13;

// Rows of `P` whose multi-index in `direction` lies in [lo, hi).
template <class Matrix>
Matrix take(const NurbsPatch& p, const Matrix& M, int direction, int lo, int hi) {
  std::vector<int> rows;
  for (int i = 0; i < p.num_control_points(); ++i) {
    const int k = p.multi_index(i)[direction];
    if (k >= lo && k < hi) rows.push_back(i);
  }
  Matrix out(rows.size(), M.cols());
  for (size_t r = 0; r < rows.size(); ++r) out.row(r) = M.row(rows[r]);
  return out;
}

}  // namespace

std::pair<NurbsPatch, NurbsPatch> split_patch(const NurbsPatch& patch, int direction, double value) {
  if (direction < 0 || direction >= patch.param_dim())
    throw SplineError(fmt::format("cannot split along direction {}: the patch has {}", direction, patch.param_dim()));
  const KnotVector& kv = patch.knots(direction);
  const double a = kv.first(), b = kv.last();
  if (!(value > a && value < b))
    throw SplineError(fmt::format("split value {} does not lie inside the parameter range ({}, {})", value, a, b));
  for (double k : kv.knots())
    if (std::abs(k - value) <= kSnapTolerance * (b - a)) value = k;
  const int p = kv.degree();
  const int present = int(std::count(kv.knots().begin(), kv.knots().end(), value));
  NurbsPatch full = patch;
  if (present < p + 1)
    full = insert_knots(patch, direction, std::vector<double>(p + 1 - present, value)).patch;

  const std::vector<double>& U = full.knots(direction).knots();
  const int first = int(std::find(U.begin(), U.end(), value) - U.begin());  // k: first copy of value
  const int n = full.num_basis(direction);
  std::vector<KnotVector> left_knots = full.all_knots(), right_knots = full.all_knots();
  left_knots[direction] = KnotVector(p, std::vector<double>(U.begin(), U.begin() + first + p + 1));
  right_knots[direction] = KnotVector(p, std::vector<double>(U.begin() + first, U.end()));
  NurbsPatch left(std::move(left_knots), take(full, full.points(), direction, 0, first),
                  take(full, Eigen::MatrixXd(full.weights()), direction, 0, first).col(0));
  NurbsPatch right(std::move(right_knots), take(full, full.points(), direction, first, n),
                   take(full, Eigen::MatrixXd(full.weights()), direction, first, n).col(0));
  return {std::move(left), std::move(right)};
}

NurbsPatch normalised(const NurbsPatch& patch) {
  std::vector<KnotVector> knots;
  for (const auto& kv : patch.all_knots()) {
    const double a = kv.first(), b = kv.last();
    std::vector<double> u = kv.knots();
    for (double& x : u) x = (x - a) / (b - a);
    u.front() = 0;  // exact ends, whatever the rounding
    u.back() = 1;
    for (int i = 0; i <= kv.degree(); ++i) {
      u[i] = 0;
      u[u.size() - 1 - i] = 1;
    }
    knots.emplace_back(kv.degree(), std::move(u));
  }
  return NurbsPatch(std::move(knots), patch.points(), patch.weights());
}

NurbsPatch reversed(const NurbsPatch& patch, int direction) {
  std::vector<KnotVector> knots = patch.all_knots();
  {
    const KnotVector& kv = knots[direction];
    std::vector<double> u(kv.knots().rbegin(), kv.knots().rend());
    for (double& x : u) x = kv.first() + kv.last() - x;
    u.front() = kv.first();  // exact ends
    u.back() = kv.last();
    knots[direction] = KnotVector(kv.degree(), std::move(u));
  }
  Eigen::MatrixXd points(patch.points().rows(), patch.points().cols());
  Eigen::VectorXd weights(patch.weights().size());
  const int n = patch.num_basis(direction);
  for (int i = 0; i < patch.num_control_points(); ++i) {
    std::array<int, 3> mi = patch.multi_index(i);
    mi[direction] = n - 1 - mi[direction];
    const int j = patch.index(mi);
    points.row(j) = patch.points().row(i);
    weights[j] = patch.weights()[i];
  }
  return NurbsPatch(std::move(knots), std::move(points), std::move(weights));
}

}  // namespace igac
