// SPDX-License-Identifier: BSD-3-Clause
#include "engine/pressure_space.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>

#include "engine/body.hpp"

namespace igac {

namespace {

// The pressure span (0-based over non-empty spans) of displacement element
// i of n along a direction coarsened `c` times: n / c spans, the last one
// taking the leftover elements; fewer than c elements: one span.
int coarse_span(int i, int n, int c) { return std::min(i / c, std::max(1, n / c) - 1); }

// The open knot vector of `degree` on every c-th breakpoint of `fine` (the
// last one always), interior knots simple: continuity C^{degree - 1}.
KnotVector coarse_knots(const KnotVector& fine, int degree, int c) {
  const std::vector<double> bp = fine.breakpoints();
  const int n = int(bp.size()) - 1, m = std::max(1, n / c);
  std::vector<double> knots(size_t(degree), bp.front());
  for (int j = 0; j < m; ++j) knots.push_back(bp[size_t(j * c)]);
  knots.insert(knots.end(), size_t(degree) + 1, bp.back());
  return KnotVector(degree, std::move(knots));
}

}  // namespace

PressureSpace::PressureSpace(const BodyQuadrature& quad, const std::vector<std::array<int, 3>>& degree,
                             const std::vector<int>& coarsening) {
  const int n_patches = quad.num_patches();
  const auto per_patch = [&](const auto& v, int k, const char* what) {
    if (v.size() != 1 && int(v.size()) != n_patches)
      throw std::invalid_argument(fmt::format("pressure space: {} {} for {} patches", v.size(), what, n_patches));
    return v[v.size() == 1 ? 0 : size_t(k)];
  };
  const int n_el = quad.num_elements();
  element_patch_.assign(size_t(n_el), 0);
  element_span_.assign(size_t(n_el), {0, 0, 0});
  element_box_.assign(size_t(n_el), {0, 0, 0, 0, 0, 0});
  int first = 0;
  std::vector<std::vector<int>> functions_of(static_cast<size_t>(n_el));
  for (int k = 0; k < n_patches; ++k) {
    const std::array<int, 3> deg = per_patch(degree, k, "degrees");
    const int c = per_patch(coarsening, k, "coarsenings");
    if (c < 1) throw std::invalid_argument(fmt::format("pressure space: coarsening {} of patch {}", c, k));
    const PatchQuadrature& pq = quad.patch_quadrature(k);
    const NurbsPatch& patch = pq.patch();
    Patch P;
    P.param_dim = patch.param_dim();
    P.first_function = first;
    const std::array<int, 3> n = pq.elements_per_direction();
    std::array<std::vector<double>, 3> bp;
    for (int d = 0; d < P.param_dim; ++d) {
      if (deg[size_t(d)] < 0)
        throw std::invalid_argument(fmt::format("pressure space: degree {} of patch {}", deg[size_t(d)], k));
      P.knots[size_t(d)] = coarse_knots(patch.knots(d), deg[size_t(d)], c);
      P.num[size_t(d)] = P.knots[size_t(d)].num_basis();
      bp[size_t(d)] = patch.knots(d).breakpoints();
      if (deg[size_t(d)] > 0 || (c > 1 && n[size_t(d)] > 1)) per_element_ = false;
      if (deg[size_t(d)] > 0) disjoint_ = false;
    }
    for (int e = 0; e < pq.num_elements(); ++e) {
      const int g = quad.first_element(k) + e;
      const std::array<int, 3> ei = pq.element_index(e);
      element_patch_[size_t(g)] = k;
      std::array<int, 3> lo{0, 0, 0}, hi{0, 0, 0};
      for (int d = 0; d < P.param_dim; ++d) {
        const int j = coarse_span(ei[size_t(d)], n[size_t(d)], c);
        element_span_[size_t(g)][size_t(d)] = deg[size_t(d)] + j;
        lo[size_t(d)] = j;
        hi[size_t(d)] = j + deg[size_t(d)];
        element_box_[size_t(g)][size_t(2 * d)] = bp[size_t(d)][size_t(ei[size_t(d)])];
        element_box_[size_t(g)][size_t(2 * d + 1)] = bp[size_t(d)][size_t(ei[size_t(d)]) + 1];
      }
      for (int i2 = lo[2]; i2 <= hi[2]; ++i2)
        for (int i1 = lo[1]; i1 <= hi[1]; ++i1)
          for (int i0 = lo[0]; i0 <= hi[0]; ++i0)
            functions_of[size_t(g)].push_back(first + i0 + P.num[0] * (i1 + P.num[1] * i2));
    }
    first += P.num[0] * P.num[1] * P.num[2];
    patches_.push_back(std::move(P));
  }
  function_patch_.assign(size_t(first), 0);
  for (int k = 0; k < n_patches; ++k)
    for (int a = patches_[size_t(k)].first_function; a < (k + 1 < n_patches ? patches_[size_t(k) + 1].first_function : first); ++a)
      function_patch_[size_t(a)] = k;
  // element -> functions, then its transpose function -> elements (increasing)
  start_.assign(size_t(first) + 1, 0);
  for (int e = 0; e < n_el; ++e) {
    for (int a : functions_of[size_t(e)]) functions_.push_back(a), ++start_[size_t(a) + 1];
    element_start_.push_back(int(functions_.size()));
  }
  for (int a = 0; a < first; ++a) start_[size_t(a) + 1] += start_[size_t(a)];
  elements_.resize(functions_.size());
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (int e = 0; e < n_el; ++e)
    for (int a : functions_of[size_t(e)]) elements_[size_t(fill[size_t(a)]++)] = e;
}

void PressureSpace::values(int e, const double* xi, std::vector<double>& out, Scratch& scratch) const {
  const Patch& P = patches_[size_t(element_patch_[size_t(e)])];
  const std::array<int, 3>& span = element_span_[size_t(e)];
  std::array<int, 3> np{1, 1, 1};
  for (int d = 0; d < P.param_dim; ++d) {
    const KnotVector& kv = P.knots[size_t(d)];
    np[size_t(d)] = kv.degree() + 1;
    kv.basis_values(span[size_t(d)], xi[d], scratch.table[size_t(d)].data());
  }
  for (int d = P.param_dim; d < 3; ++d) scratch.table[size_t(d)][0] = 1.0;
  out.resize(size_t(np[0] * np[1] * np[2]));
  size_t i = 0;
  for (int k2 = 0; k2 < np[2]; ++k2)
    for (int k1 = 0; k1 < np[1]; ++k1)
      for (int k0 = 0; k0 < np[0]; ++k0) out[i++] = scratch.table[0][size_t(k0)] * scratch.table[1][size_t(k1)] *
                                                    scratch.table[2][size_t(k2)];
}

void PressureSpace::values_local(int e, const double* s, std::vector<double>& out, Scratch& scratch) const {
  const std::array<double, 6>& box = element_box_[size_t(e)];
  double xi[3] = {0, 0, 0};
  for (int d = 0; d < patches_[size_t(element_patch_[size_t(e)])].param_dim; ++d)
    xi[d] = box[size_t(2 * d)] + s[d] * (box[size_t(2 * d + 1)] - box[size_t(2 * d)]);
  values(e, xi, out, scratch);
}

PressureSpace mixed_pressure_space(const BodyQuadrature& quad, const std::vector<Formulation>& patch_formulations) {
  const int n = quad.num_patches();
  std::vector<std::array<int, 3>> degree(size_t(n), {0, 0, 0});
  std::vector<int> coarsening(size_t(n), 1);
  for (int k = 0; k < n; ++k) {
    const Formulation f = patch_formulations.empty()       ? Formulation::displacement
                          : patch_formulations.size() == 1 ? patch_formulations[0]
                                                           : patch_formulations.at(size_t(k));
    if (f != Formulation::mixed) continue;  // mixed_element and displacement: constants per element
    const NurbsPatch& patch = quad.patch_quadrature(k).patch();
    for (int d = 0; d < patch.param_dim(); ++d) degree[size_t(k)][size_t(d)] = std::max(0, patch.degree(d) - 1);
    coarsening[size_t(k)] = kPressureCoarsening;
  }
  return PressureSpace(quad, degree, coarsening);
}

}  // namespace igac
