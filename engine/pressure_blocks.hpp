// SPDX-License-Identifier: BSD-3-Clause
// The pressure blocks of the mixed formulation: each patch's elements grouped
// into blocks of 2 x 2 (x 2) neighbouring elements in the parametric
// directions, one pressure (and one dilatation) per block.  Constants per
// element are not inf-sup stable with C^{p-1} NURBS displacements (the
// discrete inf-sup constant falls like h); constants per 2 x 2 block are
// (docs/benchmarks.md, "Inf-sup").
//
// Rule, per patch and per parametric direction of n elements (non-empty
// knot spans): n / width blocks of `width` elements, the last one also
// taking the n % width leftover elements (so an odd n = 5 at width 2 gives
// blocks of 2 and 3), and a direction of fewer than `width` elements one
// block of all of them.  Blocks never cross a patch boundary: a multi-patch
// body has blocks per patch.  Width 1: one block per element (the patches
// in the displacement formulation, which carry no pressure, and so pay
// nothing: their elements are blocks of one).
//
// Elements are numbered as BodyQuadrature numbers them; a block lists its
// elements in increasing number.  Blocks are numbered patch after patch,
// first parametric direction fastest.
#pragma once

#include <vector>

#include "engine/body.hpp"
#include "engine/volumetric_projection.hpp"

namespace igac {

struct ElementBlocks {
  std::vector<int> block_of;      // per element: its block
  std::vector<int> start{0};      // elements of block b: elements[start[b]] ... elements[start[b + 1] - 1]
  std::vector<int> elements;
  int num_blocks() const { return int(start.size()) - 1; }
  int num_elements() const { return int(block_of.size()); }
  // Whether every block is a single element (nothing to widen or to pass twice).
  bool per_element() const { return num_blocks() == num_elements(); }
};

// The blocks of `quad`'s elements, patch k grouped width_per_patch[k] wide in
// every direction (one entry: every patch's width).  Throws
// std::invalid_argument for a width < 1 or a list of the wrong length.
ElementBlocks block_elements(const BodyQuadrature& quad, const std::vector<int>& width_per_patch);

// The mixed formulation's pressure blocks: patches in the mixed formulation
// 2 wide, the others (mixed_element and displacement) 1 (patch_formulations: one entry, every patch's; empty,
// displacement everywhere).  The one definition every consumer uses (the
// assemblies, the u-p Newton's unknowns, the state file, the recovered
// pressure field), so a block number means the same block everywhere.
inline constexpr int kPressureBlockWidth = 2;
ElementBlocks mixed_pressure_blocks(const BodyQuadrature& quad, const std::vector<Formulation>& patch_formulations);

}  // namespace igac
