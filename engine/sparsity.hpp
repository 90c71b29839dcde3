// SPDX-License-Identifier: BSD-3-Clause
// The sparsity pattern of the matrices of a body and the scatter of element
// vectors and matrices into the global ones by the element's dof indices
// (DofMap::element_equations): the one pattern and the one scatter of the
// linear (assembly.cpp) and the total-Lagrangian (total_lagrangian.cpp)
// assembly, the follower pressure (follower_pressure.cpp) and the obstacle
// curvature of the large-deformation contact (contact/); and the element
// colouring both assemblies thread over.
//
// Pattern: free equations r and c are coupled when their control points
// share an element; the matrix is compressed, column major, with sorted row
// indices and zero values, and symmetric in structure.  A driver analyses it
// once (symbolic factorisation) and every matrix assembled into it has the
// same structure.
#pragma once

#include <Eigen/Sparse>
#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>
#include <vector>

#include "engine/assembly.hpp"
#include "engine/pressure_space.hpp"

namespace igac {

// The coupling pattern of elements [e_begin, e_end) of `quad` (e_end < 0:
// to the last one) in the free numbering of `dofs` (n_free x n_free).
Eigen::SparseMatrix<double> coupling_pattern(const BodyQuadrature& quad, const DofMap& dofs, int e_begin = 0,
                                             int e_end = -1);

// The pattern of elements [e_begin, e_end) with, in addition, the control
// points of each pressure function's support coupled together (the mixed
// formulation's rank-one term per function, pressure_space.hpp, reaches
// every control point of its support).  A function belongs to the range
// holding the first element of its support, and reaches its other elements
// wherever they lie (a distributed assembly evaluates them again).  A space
// of constants per element gives the element pattern.
Eigen::SparseMatrix<double> coupling_pattern(const BodyQuadrature& quad, const DofMap& dofs,
                                             const PressureSpace& space, int e_begin = 0, int e_end = -1);

// Elements [e_begin, e_end) of `quad` (e_end < 0: to the last one) in
// colours such that no two elements of one colour write to the same free
// equation (greedy colouring of the element graph; coincident control points
// of a collapsed face write to one equation, so conflicts are counted in
// equations, not control points).  Threads then add straight into K and f,
// colour by colour: no per-thread copies of the matrix (whose memory would
// grow with the thread count) and no reduction, and the sums do not depend
// on the number of threads.  A tensor mesh of degree p needs (p+1)^dim
// colours.  Element numbers are those of `quad`.
std::vector<std::vector<int>> colour_elements(const BodyQuadrature& quad, const DofMap& dofs, int e_begin = 0,
                                              int e_end = -1);


// The pressure functions the range [e_begin, e_end) owns (as above) in
// colours such that no two functions of one colour write to the same free
// equation: function numbers by colour, for the loop over functions that adds
// each one's rank-one term.
std::vector<std::vector<int>> colour_functions(const BodyQuadrature& quad, const DofMap& dofs,
                                               const PressureSpace& space, int e_begin = 0, int e_end = -1);

// f[eq[r]] += fe[r] for every local row r with a free equation (prescribed
// ones, -1, are skipped).
template <class ElementVector>
void scatter_element_vector(const std::vector<int>& eq, const ElementVector& fe, double* f) {
  for (int r = 0; r < int(eq.size()); ++r)
    if (eq[r] >= 0) f[eq[r]] += fe[r];
}

// values[k] += Ke(r, c) for every local row r and column c whose free
// equations eq[r], eq[c] are >= 0 (prescribed ones, -1, are skipped), at the
// entry (eq[r], eq[c]) of `pattern` (compressed, column major, sorted).  The
// components of a control point are consecutive equations, hence usually
// consecutive entries of a column: a step forward is tried before a binary
// search.  Throws std::logic_error when the pattern lacks an entry.
template <class ElementMatrix>
void scatter_element_matrix(const Eigen::SparseMatrix<double>& pattern, double* values, const std::vector<int>& eq,
                            const ElementMatrix& Ke) {
  const int* outer = pattern.outerIndexPtr();
  const int* inner = pattern.innerIndexPtr();
  const int nd = int(eq.size());
  for (int c = 0; c < nd; ++c) {
    if (eq[c] < 0) continue;
    const int* first = inner + outer[eq[c]];
    const int* past = inner + outer[eq[c] + 1];
    const int* pos = past;
    for (int r = 0; r < nd; ++r) {
      const int row = eq[r];
      if (row < 0) continue;
      if (pos + 1 < past && pos[1] == row)
        ++pos;
      else
        pos = std::lower_bound(first, past, row);
      if (pos == past || *pos != row) [[unlikely]]
        throw std::logic_error(fmt::format("scatter: the matrix has no entry ({}, {})", row, eq[c]));
      values[pos - inner] += Ke(r, c);
    }
  }
}

}  // namespace igac
