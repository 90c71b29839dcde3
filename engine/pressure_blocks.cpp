// SPDX-License-Identifier: BSD-3-Clause
#include "engine/pressure_blocks.hpp"

#include <algorithm>
#include <array>
#include <fmt/format.h>
#include <stdexcept>

namespace igac {

namespace {

// The block along one direction of n elements, `width` wide, of element i.
int block_along(int i, int n, int width) {
  const int count = std::max(1, n / width);
  return std::min(i / width, count - 1);
}

int blocks_along(int n, int width) { return std::max(1, n / width); }

}  // namespace

ElementBlocks block_elements(const BodyQuadrature& quad, const std::vector<int>& width_per_patch) {
  const int n_patches = quad.num_patches();
  if (width_per_patch.size() != 1 && int(width_per_patch.size()) != n_patches)
    throw std::invalid_argument(
        fmt::format("pressure blocks: {} widths for {} patches", width_per_patch.size(), n_patches));
  ElementBlocks out;
  out.block_of.assign(size_t(quad.num_elements()), -1);
  int first_block = 0;
  for (int k = 0; k < n_patches; ++k) {
    const int width = width_per_patch.size() == 1 ? width_per_patch[0] : width_per_patch[k];
    if (width < 1) throw std::invalid_argument(fmt::format("pressure blocks: width {} of patch {}", width, k));
    const PatchQuadrature& pq = quad.patch_quadrature(k);
    const std::array<int, 3> n = pq.elements_per_direction();
    const std::array<int, 3> nb{blocks_along(n[0], width), blocks_along(n[1], width), blocks_along(n[2], width)};
    for (int e = 0; e < pq.num_elements(); ++e) {
      const std::array<int, 3> ei = pq.element_index(e);
      const int b = block_along(ei[0], n[0], width) +
                    nb[0] * (block_along(ei[1], n[1], width) + nb[1] * block_along(ei[2], n[2], width));
      out.block_of[size_t(quad.first_element(k) + e)] = first_block + b;
    }
    first_block += nb[0] * nb[1] * nb[2];
  }
  // blocks -> elements (CSR, elements increasing within a block)
  out.start.assign(size_t(first_block) + 1, 0);
  for (int b : out.block_of) ++out.start[size_t(b) + 1];
  for (int b = 0; b < first_block; ++b) out.start[size_t(b) + 1] += out.start[size_t(b)];
  out.elements.resize(out.block_of.size());
  std::vector<int> fill(out.start.begin(), out.start.end() - 1);
  for (int e = 0; e < int(out.block_of.size()); ++e) out.elements[size_t(fill[size_t(out.block_of[e])]++)] = e;
  return out;
}

ElementBlocks mixed_pressure_blocks(const BodyQuadrature& quad, const std::vector<Formulation>& patch_formulations) {
  std::vector<int> widths(size_t(quad.num_patches()), 1);
  for (int k = 0; k < quad.num_patches(); ++k) {
    const Formulation f = patch_formulations.empty()       ? Formulation::displacement
                          : patch_formulations.size() == 1 ? patch_formulations[0]
                                                           : patch_formulations.at(size_t(k));
    if (f == Formulation::mixed) widths[size_t(k)] = kPressureBlockWidth;  // mixed_element: blocks of one
  }
  return block_elements(quad, widths);
}

}  // namespace igac
