// SPDX-License-Identifier: BSD-3-Clause
#include "engine/sparsity.hpp"
#include "engine/free_cores.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>

namespace igac {

namespace {

// The units of a pattern or a colouring: elements, or the supports of
// pressure functions (pressure_space.hpp), each with its control points
// (CSR, each point once).
struct Units {
  std::vector<int> start{0}, cps;
  std::vector<int> id;  // the element or function number of each unit
  int size() const { return int(start.size()) - 1; }
};

Units element_units(const BodyQuadrature& quad, int e_begin, int e_end) {
  Units u;
  std::vector<int> cps;
  for (int e = e_begin; e < e_end; ++e) {
    quad.control_points(e, cps);
    if (cps.empty()) throw std::logic_error("coupling pattern: an element without control points");
    u.cps.insert(u.cps.end(), cps.begin(), cps.end());
    u.start.push_back(int(u.cps.size()));
    u.id.push_back(e);
  }
  return u;
}

// The units of elements [e_begin, e_end) and of the pressure functions the
// range owns (pressure_space.hpp: a function belongs to the range holding
// the first element of its support, whose other elements it reaches
// wherever they lie), in that order.  With `elements` false only the
// functions.
Units space_units(const BodyQuadrature& quad, const PressureSpace& space, int e_begin, int e_end, bool elements) {
  if (space.num_elements() != quad.num_elements())
    throw std::logic_error("coupling pattern: a pressure space of another body");
  Units u = elements ? element_units(quad, e_begin, e_end) : Units{};
  std::vector<int> cps;
  for (int a = 0; a < space.num_functions(); ++a) {
    const int* first = space.support_begin(a);
    if (first == space.support_end(a) || *first < e_begin || *first >= e_end) continue;
    const size_t from = u.cps.size();
    for (const int* e = first; e != space.support_end(a); ++e) {
      quad.control_points(*e, cps);
      u.cps.insert(u.cps.end(), cps.begin(), cps.end());
    }
    std::sort(u.cps.begin() + std::ptrdiff_t(from), u.cps.end());
    u.cps.erase(std::unique(u.cps.begin() + std::ptrdiff_t(from), u.cps.end()), u.cps.end());
    u.start.push_back(int(u.cps.size()));
    u.id.push_back(a);
  }
  return u;
}

// Sparsity pattern (free numbering, values zero): equations couple when their
// control points share a unit.  Built per node rather than per unit pair, so
// the temporary memory stays at the size of the result: a node is a control
// point with its free equations, coincident control points of a collapsed
// face (same equations) being one node, keyed by its first free equation.
// Symmetric, so column r's rows are row r's columns.
Eigen::SparseMatrix<double> pattern_of_units(const Units& units, const DofMap& dofs) {
  const int dim = dofs.dim(), n_free = dofs.num_free();
  const int n_cp = dofs.num_dofs() / dim, n_units = units.size();

  // control point -> units (CSR)
  std::vector<int> cp_start(n_cp + 1, 0);
  for (int a : units.cps) ++cp_start[a + 1];
  for (int a = 0; a < n_cp; ++a) cp_start[a + 1] += cp_start[a];
  std::vector<int> cp_units(cp_start[n_cp]), fill(cp_start.begin(), cp_start.end() - 1);
  for (int e = 0; e < n_units; ++e)
    for (int k = units.start[e]; k < units.start[e + 1]; ++k) cp_units[fill[units.cps[k]]++] = e;

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
  // distinct neighbours are sorted, not every unit's copy of them)
  std::vector<std::vector<int>> cols(n_free);
#pragma omp parallel num_threads(free_cores())
  {
    std::vector<int> seen(n_cp, -1);
#pragma omp for schedule(dynamic, 256)
    for (int r = 0; r < n_free; ++r) {
      auto& v = cols[r];
      for (int a : node_cps[r])
        for (int k = cp_start[a]; k < cp_start[a + 1]; ++k) {
          const int e = cp_units[k];
          for (int j = units.start[e]; j < units.start[e + 1]; ++j) {
            const int b = units.cps[j];
            if (seen[b] == r) continue;
            seen[b] = r;
            for (int i = 0; i < dim; ++i)
              if (const int q = dofs.equation(b * dim + i); q >= 0) v.push_back(q);
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

// Greedy colouring of the units: no two units of a colour write to the same
// free equation.  Returns the units' ids by colour.
std::vector<std::vector<int>> colour_units(const Units& units, const DofMap& dofs) {
  const int dim = dofs.dim(), n_free = dofs.num_free(), n_units = units.size();
  // unit -> the equations it writes (one per node: its first free one)
  std::vector<int> start(n_units + 1, 0), keys;
  for (int e = 0; e < n_units; ++e) {
    const size_t first = keys.size();
    for (int k = units.start[e]; k < units.start[e + 1]; ++k)
      for (int i = 0; i < dim; ++i)
        if (const int q = dofs.equation(units.cps[k] * dim + i); q >= 0) {
          keys.push_back(q);
          break;
        }
    std::sort(keys.begin() + std::ptrdiff_t(first), keys.end());
    keys.erase(std::unique(keys.begin() + std::ptrdiff_t(first), keys.end()), keys.end());
    start[e + 1] = int(keys.size());
  }
  // equation -> units (CSR)
  std::vector<int> key_start(n_free + 1, 0);
  for (int k : keys) ++key_start[k + 1];
  for (int q = 0; q < n_free; ++q) key_start[q + 1] += key_start[q];
  std::vector<int> key_units(keys.size()), fill(key_start.begin(), key_start.end() - 1);
  for (int e = 0; e < n_units; ++e)
    for (int k = start[e]; k < start[e + 1]; ++k) key_units[fill[keys[k]]++] = e;
  std::vector<int> colour(n_units, -1), stamp;  // stamp[c] == e: colour c taken by a neighbour of e
  std::vector<std::vector<int>> out;
  for (int e = 0; e < n_units; ++e) {
    for (int k = start[e]; k < start[e + 1]; ++k)
      for (int j = key_start[keys[k]]; j < key_start[keys[k] + 1]; ++j)
        if (const int c = colour[key_units[j]]; c >= 0) stamp[c] = e;
    int c = 0;
    while (c < int(stamp.size()) && stamp[c] == e) ++c;
    if (c == int(stamp.size())) {
      stamp.push_back(-1);
      out.emplace_back();
    }
    colour[e] = c;
    out[c].push_back(units.id[e]);
  }
  return out;
}

}  // namespace

Eigen::SparseMatrix<double> coupling_pattern(const BodyQuadrature& quad, const DofMap& dofs, int e_begin, int e_end) {
  if (e_end < 0) e_end = quad.num_elements();
  return pattern_of_units(element_units(quad, e_begin, e_end), dofs);
}

std::vector<std::vector<int>> colour_elements(const BodyQuadrature& quad, const DofMap& dofs, int e_begin, int e_end) {
  if (e_end < 0) e_end = quad.num_elements();
  return colour_units(element_units(quad, e_begin, e_end), dofs);
}

Eigen::SparseMatrix<double> coupling_pattern(const BodyQuadrature& quad, const DofMap& dofs,
                                             const PressureSpace& space, int e_begin, int e_end) {
  if (e_end < 0) e_end = quad.num_elements();
  if (space.per_element()) return coupling_pattern(quad, dofs, e_begin, e_end);
  return pattern_of_units(space_units(quad, space, e_begin, e_end, true), dofs);
}

std::vector<std::vector<int>> colour_functions(const BodyQuadrature& quad, const DofMap& dofs,
                                               const PressureSpace& space, int e_begin, int e_end) {
  if (e_end < 0) e_end = quad.num_elements();
  return colour_units(space_units(quad, space, e_begin, e_end, false), dofs);
}

}  // namespace igac
