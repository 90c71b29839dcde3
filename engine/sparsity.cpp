// SPDX-License-Identifier: BSD-3-Clause
#include "engine/sparsity.hpp"

#include <algorithm>
#include <stdexcept>

namespace igac {

// Sparsity pattern (free numbering, values zero): equations couple when their
// control points share an element.  Built per node rather than per element
// pair, so the temporary memory stays at the size of the result: a node is a
// control point with its free equations, coincident control points of a
// collapsed face (same equations) being one node, keyed by its first free
// equation.  Symmetric, so column r's rows are row r's columns.
Eigen::SparseMatrix<double> coupling_pattern(const BodyQuadrature& quad, const DofMap& dofs, int e_begin, int e_end) {
  if (e_end < 0) e_end = quad.num_elements();
  const int dim = dofs.dim(), n_free = dofs.num_free();
  const int n_cp = dofs.num_dofs() / dim, n_el = e_end - e_begin, nl = quad.num_local();

  // element -> control points, and control point -> elements (CSR)
  std::vector<int> el_cps(size_t(n_el) * nl), cps;
  std::vector<int> cp_start(n_cp + 1, 0);
  for (int e = 0; e < n_el; ++e) {
    quad.control_points(e_begin + e, cps);
    if (int(cps.size()) > nl || cps.empty()) throw std::logic_error("coupling pattern: an element larger than num_local");
    // A patch of a lower degree (a second body): its elements padded with
    // their first control point, which couples nothing new.
    cps.resize(size_t(nl), cps.front());
    std::copy(cps.begin(), cps.end(), el_cps.begin() + size_t(e) * nl);
    for (int a : cps) ++cp_start[a + 1];
  }
  for (int a = 0; a < n_cp; ++a) cp_start[a + 1] += cp_start[a];
  std::vector<int> cp_els(cp_start[n_cp]), fill(cp_start.begin(), cp_start.end() - 1);
  for (int e = 0; e < n_el; ++e)
    for (int k = 0; k < nl; ++k) cp_els[fill[el_cps[size_t(e) * nl + k]]++] = e;

  // node (first free equation) -> its control points
  auto first_free = [&](int a) {
    for (int i = 0; i < dim; ++i)
      if (dofs.equation(a * dim + i) >= 0) return dofs.equation(a * dim + i);
    return -1;
  };
  std::vector<std::vector<int>> node_cps(n_free);
  for (int a = 0; a < n_cp; ++a)
    if (const int r = first_free(a); r >= 0) node_cps[r].push_back(a);

  // per node: the sorted free equations of every control point it meets
  // (each control point once: a stamp per thread, so only the 3^d p-ish
  // distinct neighbours are sorted, not every element's copy of them)
  std::vector<std::vector<int>> cols(n_free);
#pragma omp parallel
  {
    std::vector<int> seen(n_cp, -1);
#pragma omp for schedule(dynamic, 256)
    for (int r = 0; r < n_free; ++r) {
      auto& v = cols[r];
      for (int a : node_cps[r])
        for (int k = cp_start[a]; k < cp_start[a + 1]; ++k) {
          const int* c = el_cps.data() + size_t(cp_els[k]) * nl;
          for (int b = 0; b < nl; ++b) {
            if (seen[c[b]] == r) continue;
            seen[c[b]] = r;
            for (int j = 0; j < dim; ++j)
              if (const int q = dofs.equation(c[b] * dim + j); q >= 0) v.push_back(q);
          }
        }
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());  // coincident control points share equations
    }
  }

  // every free equation of a node has the node's columns
  std::vector<int> node_of(n_free, -1);
  for (int r = 0; r < n_free; ++r)
    for (int a : node_cps[r])
      for (int i = 0; i < dim; ++i)
        if (const int q = dofs.equation(a * dim + i); q >= 0) node_of[q] = r;
  Eigen::SparseMatrix<double> K(n_free, n_free);
  std::vector<Eigen::Index> outer(n_free + 1, 0);
  for (int q = 0; q < n_free; ++q) outer[q + 1] = outer[q] + Eigen::Index(cols[node_of[q]].size());
  K.resizeNonZeros(outer[n_free]);
  for (int q = 0; q <= n_free; ++q) K.outerIndexPtr()[q] = int(outer[q]);
  for (int q = 0; q < n_free; ++q) std::copy(cols[node_of[q]].begin(), cols[node_of[q]].end(), K.innerIndexPtr() + outer[q]);
  std::fill(K.valuePtr(), K.valuePtr() + outer[n_free], 0.0);
  return K;
}

std::vector<std::vector<int>> colour_elements(const BodyQuadrature& quad, const DofMap& dofs, int e_begin, int e_end) {
  if (e_end < 0) e_end = quad.num_elements();
  const int dim = dofs.dim(), n_free = dofs.num_free(), n_el = e_end - e_begin;
  // element -> the equations it writes (one per node: its first free one)
  std::vector<int> start(n_el + 1, 0), keys, cps;
  for (int e = 0; e < n_el; ++e) {
    quad.control_points(e_begin + e, cps);
    const size_t first = keys.size();
    for (int a : cps)
      for (int i = 0; i < dim; ++i)
        if (const int q = dofs.equation(a * dim + i); q >= 0) {
          keys.push_back(q);
          break;
        }
    std::sort(keys.begin() + first, keys.end());
    keys.erase(std::unique(keys.begin() + first, keys.end()), keys.end());
    start[e + 1] = int(keys.size());
  }
  // equation -> elements (CSR)
  std::vector<int> key_start(n_free + 1, 0);
  for (int k : keys) ++key_start[k + 1];
  for (int q = 0; q < n_free; ++q) key_start[q + 1] += key_start[q];
  std::vector<int> key_els(keys.size()), fill(key_start.begin(), key_start.end() - 1);
  for (int e = 0; e < n_el; ++e)
    for (int k = start[e]; k < start[e + 1]; ++k) key_els[fill[keys[k]]++] = e;
  std::vector<int> colour(n_el, -1), stamp;  // stamp[c] == e: colour c taken by a neighbour of e
  std::vector<std::vector<int>> out;
  for (int e = 0; e < n_el; ++e) {
    for (int k = start[e]; k < start[e + 1]; ++k)
      for (int j = key_start[keys[k]]; j < key_start[keys[k] + 1]; ++j)
        if (const int c = colour[key_els[j]]; c >= 0) stamp[c] = e;
    int c = 0;
    while (c < int(stamp.size()) && stamp[c] == e) ++c;
    if (c == int(stamp.size())) {
      stamp.push_back(-1);
      out.emplace_back();
    }
    colour[e] = c;
    out[c].push_back(e_begin + e);
  }
  return out;
}

}  // namespace igac
