// SPDX-License-Identifier: BSD-3-Clause
#include "engine/spline/knot_vector.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace igac {

namespace {
// Two knots closer than this (relative to the range) are the same breakpoint.
constexpr double kKnotTolerance = 1e-13;
// A breakpoint of a refinement this close (relative to the range) to one of
// the refined knot vector's is taken to be that one (united_with).
constexpr double kKnotSnap = 1e-10;
}  // namespace

KnotVector::KnotVector(int degree, std::vector<double> knots)
    : degree_(degree), knots_(std::move(knots)) {
  validate();
}

void KnotVector::validate() const {
  if (degree_ < 0) throw SplineError(fmt::format("degree {} is negative", degree_));
  const int n = size();
  if (n < 2 * (degree_ + 1))
    throw SplineError(fmt::format("a knot vector of degree {} needs at least {} knots, got {}",
                                  degree_, 2 * (degree_ + 1), n));
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(knots_[i])) throw SplineError(fmt::format("knot {} is not finite", i));
  for (int i = 1; i < n; ++i)
    if (knots_[i] < knots_[i - 1])
      throw SplineError(fmt::format("knots decrease at position {} ({} after {})", i,
                                    knots_[i], knots_[i - 1]));
  if (!(last() > first())) throw SplineError("knot vector has zero length");
  for (int i = 1; i <= degree_; ++i) {
    if (knots_[i] != knots_[0] || knots_[n - 1 - i] != knots_[n - 1])
      throw SplineError(fmt::format(
          "knot vector is not open: the first and last knots must each be repeated "
          "{} times (degree + 1)", degree_ + 1));
  }
  if (knots_[degree_ + 1] == knots_[0] || knots_[n - 2 - degree_] == knots_[n - 1])
    throw SplineError(fmt::format("an end knot is repeated more than {} times (degree + 1)",
                                  degree_ + 1));
  const auto m = multiplicities();
  for (size_t j = 1; j + 1 < m.size(); ++j)
    if (m[j] > degree_ + 1)
      throw SplineError(fmt::format("interior knot {} has multiplicity {} > degree + 1 = {}",
                                    breakpoints()[j], m[j], degree_ + 1));
}

KnotVector KnotVector::uniform(int degree, int n_elements) {
  if (n_elements < 1) throw SplineError(fmt::format("need at least one element, got {}", n_elements));
  std::vector<double> k(degree + 1, 0.0);
  for (int e = 1; e < n_elements; ++e) k.push_back(double(e) / n_elements);
  k.insert(k.end(), degree + 1, 1.0);
  return KnotVector(degree, std::move(k));
}

namespace {
// The ratio r > 1 with h (r + r^2 + ... + r^n) = L, for n h < L.
double geometric_ratio(double h, int n, double L) {
  auto filled = [&](double r) {
    double s = 0, t = 1;
    for (int k = 0; k < n; ++k) s += (t *= r);
    return h * s;
  };
  double lo = 1, hi = 2;
  while (filled(hi) < L) hi *= 2;
  for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (filled(mid) < L ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}
}  // namespace

KnotVector KnotVector::graded(int degree, int n_elements, double span_fraction,
                              double range_fraction, bool at_start, CoarseSpans coarse) {
  if (!(span_fraction > 0 && span_fraction < 1))
    throw SplineError(fmt::format("grading span fraction {} must lie in (0, 1)", span_fraction));
  if (!(range_fraction > 0 && range_fraction < 1))
    throw SplineError(fmt::format("grading range fraction {} must lie in (0, 1)", range_fraction));
  if (n_elements < 2) throw SplineError("a graded knot vector needs at least two elements");
  const int n_fine = std::clamp(int(std::lround(span_fraction * n_elements)), 1, n_elements - 1);
  const int n_coarse = n_elements - n_fine;
  std::vector<double> inner;  // interior breakpoints, measured from the graded end
  for (int e = 1; e <= n_fine; ++e) inner.push_back(range_fraction * e / n_fine);
  const double h_fine = range_fraction / n_fine, rest = 1 - range_fraction;
  if (coarse == CoarseSpans::geometric && n_coarse * h_fine < rest) {
    const double r = geometric_ratio(h_fine, n_coarse, rest);
    double x = range_fraction, h = h_fine;
    for (int e = 1; e < n_coarse; ++e) inner.push_back(x += (h *= r));
  } else {
    for (int e = 1; e < n_coarse; ++e) inner.push_back(range_fraction + rest * e / n_coarse);
  }
  if (!at_start) {
    for (double& x : inner) x = 1 - x;
    std::reverse(inner.begin(), inner.end());
  }
  std::vector<double> k(degree + 1, 0.0);
  k.insert(k.end(), inner.begin(), inner.end());
  k.insert(k.end(), degree + 1, 1.0);
  return KnotVector(degree, std::move(k));
}

std::vector<double> KnotVector::breakpoints() const {
  std::vector<double> b{knots_.front()};
  const double tol = kKnotTolerance * (last() - first());
  for (double x : knots_)
    if (x - b.back() > tol) b.push_back(x);
  return b;
}

std::vector<int> KnotVector::multiplicities() const {
  std::vector<int> m{0};
  double cur = knots_.front();
  const double tol = kKnotTolerance * (last() - first());
  for (double x : knots_) {
    if (x - cur > tol) { m.push_back(0); cur = x; }
    ++m.back();
  }
  return m;
}

int KnotVector::find_span(double u) const {
  const int n = num_basis();  // spans degree .. n-1 are the valid ones
  if (u >= knots_[n]) return n - 1;
  if (u <= knots_[degree_]) {
    int s = degree_;
    while (knots_[s + 1] <= u) ++s;
    return s;
  }
  // upper_bound: first knot > u; the span starts one before it.
  auto it = std::upper_bound(knots_.begin() + degree_, knots_.begin() + n + 1, u);
  return int(it - knots_.begin()) - 1;
}

std::vector<int> KnotVector::element_spans() const {
  std::vector<int> s;
  for (int i = degree_; i < num_basis(); ++i)
    if (knots_[i + 1] > knots_[i]) s.push_back(i);
  return s;
}

void KnotVector::basis_values(int span, double u, double* out) const {
  // Piegl & Tiller A2.2.
  const int p = degree_;
  if (p >= 15) throw SplineError(fmt::format("degree {} is above the supported 14", p));
  double left[16], right[16];
  out[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - knots_[size_t(span + 1 - j)];
    right[j] = knots_[size_t(span + j)] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = out[r] / (right[r + 1] + left[j - r]);
      out[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    out[j] = saved;
  }
}

void KnotVector::basis_derivatives(int span, double u, int n_derivs,
                                   std::vector<std::vector<double>>& ders) const {
  // Piegl & Tiller A2.3.
  const int p = degree_;
  const auto& U = knots_;
  double ndu[16][16], a[2][16], left[16], right[16];
  if (p >= 15) throw SplineError(fmt::format("degree {} is above the supported 14", p));
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  ders.assign(n_derivs + 1, std::vector<double>(p + 1, 0.0));
  for (int j = 0; j <= p; ++j) ders[0][j] = ndu[j][p];
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= std::min(n_derivs, p); ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k][r] = d;
      std::swap(s1, s2);
    }
  }
  double r = p;
  for (int k = 1; k <= std::min(n_derivs, p); ++k) {
    for (int j = 0; j <= p; ++j) ders[k][j] *= r;
    r *= (p - k);
  }
}

std::vector<double> KnotVector::greville() const {
  std::vector<double> g(num_basis());
  for (int i = 0; i < num_basis(); ++i) {
    double s = 0;
    for (int j = 1; j <= degree_; ++j) s += knots_[i + j];
    g[i] = degree_ > 0 ? s / degree_ : 0.5 * (knots_[i] + knots_[i + 1]);
  }
  return g;
}

KnotVector KnotVector::elevated(int by) const {
  const auto b = breakpoints();
  const auto m = multiplicities();
  std::vector<double> k;
  for (size_t j = 0; j < b.size(); ++j) k.insert(k.end(), m[j] + by, b[j]);
  return KnotVector(degree_ + by, std::move(k));
}

KnotVector KnotVector::subdivided(int parts) const {
  if (parts < 1) throw SplineError(fmt::format("cannot split spans into {} parts", parts));
  const auto b = breakpoints();
  const auto m = multiplicities();
  std::vector<double> k;
  for (size_t j = 0; j < b.size(); ++j) {
    k.insert(k.end(), m[j], b[j]);
    if (j + 1 < b.size())
      for (int q = 1; q < parts; ++q) k.push_back(b[j] + (b[j + 1] - b[j]) * q / parts);
  }
  return KnotVector(degree_, std::move(k));
}

std::vector<double> KnotVector::knots_missing_from(const KnotVector& finer) const {
  std::vector<double> out;
  size_t i = 0;
  const double tol = kKnotTolerance * (last() - first());
  for (double x : finer.knots()) {
    if (i < knots_.size() && std::abs(knots_[i] - x) <= tol) { ++i; continue; }
    out.push_back(x);
  }
  if (i != knots_.size()) throw SplineError("refined knot vector does not contain the original one");
  return out;
}

KnotVector KnotVector::united_with(const KnotVector& kept) const {
  if (kept.degree() != degree_ || std::abs(kept.first() - first()) > kKnotSnap * (last() - first()) ||
      std::abs(kept.last() - last()) > kKnotSnap * (last() - first()))
    throw SplineError(fmt::format("cannot unite knot vectors of degree {} on [{}, {}] and degree {} on [{}, {}]", degree_,
                                  first(), last(), kept.degree(), kept.first(), kept.last()));
  const double snap = kKnotSnap * (last() - first());
  const auto kb = kept.breakpoints();
  const auto km = kept.multiplicities();
  std::vector<std::pair<double, int>> united;  // (breakpoint, multiplicity)
  for (size_t i = 0; i < kb.size(); ++i) united.emplace_back(kb[i], km[i]);
  const auto b = breakpoints();
  const auto m = multiplicities();
  for (size_t j = 0; j < b.size(); ++j) {
    auto same = std::find_if(united.begin(), united.begin() + kb.size(),
                             [&](const auto& u) { return std::abs(u.first - b[j]) <= snap; });
    if (same != united.begin() + kb.size()) same->second = std::max(same->second, m[j]);
    else united.emplace_back(b[j], m[j]);
  }
  std::sort(united.begin(), united.end());
  std::vector<double> k;
  for (const auto& [x, mult] : united) k.insert(k.end(), mult, x);
  if (k == knots_) return *this;
  return KnotVector(degree_, std::move(k));
}

}  // namespace igac
