// SPDX-License-Identifier: BSD-3-Clause
// The pressure blocks of the mixed formulation (engine/pressure_blocks.hpp)
// and the pattern and colouring over blocks (engine/sparsity.hpp): the
// blocking rule on even, odd and short directions and on several patches,
// and the block pattern against a brute-force one.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "engine/geometry/shapes.hpp"
#include "engine/pressure_blocks.hpp"
#include "engine/sparsity.hpp"
#include "engine/spline/refinement.hpp"

namespace igac {
namespace {

NurbsPatch square(int parts) { return subdivide(elevate_to(rectangle(1, 1).patch, 2), parts); }

// The parametric index range of each block's elements along each direction.
std::vector<std::array<std::pair<int, int>, 3>> extents(const BodyQuadrature& quad, const ElementBlocks& blocks) {
  std::vector<std::array<std::pair<int, int>, 3>> out(size_t(blocks.num_blocks()));
  for (int b = 0; b < blocks.num_blocks(); ++b) {
    auto& ext = out[size_t(b)];
    ext.fill({1 << 20, -1});
    for (int k = blocks.start[b]; k < blocks.start[b + 1]; ++k) {
      const int e = blocks.elements[k];
      const int patch = quad.patch_of(e);
      const auto ei = quad.patch_quadrature(patch).element_index(e - quad.first_element(patch));
      for (int d = 0; d < 3; ++d) ext[d] = {std::min(ext[d].first, ei[d]), std::max(ext[d].second, ei[d])};
    }
  }
  return out;
}

TEST(PressureBlocks, TwoByTwoWithTheOddLeftoverInTheLastBlock) {
  const Body body(square(5));  // 5 x 5: blocks of 2 and 3 elements per direction
  const BodyQuadrature quad(body, 3);
  const ElementBlocks blocks = block_elements(quad, {2});
  ASSERT_EQ(blocks.num_blocks(), 4);
  EXPECT_FALSE(blocks.per_element());
  std::multiset<int> sizes;
  for (int b = 0; b < 4; ++b) sizes.insert(blocks.start[b + 1] - blocks.start[b]);
  EXPECT_EQ(sizes, (std::multiset<int>{4, 6, 6, 9}));
  // each block a full rectangle of neighbouring elements
  const auto ext = extents(quad, blocks);
  for (int b = 0; b < 4; ++b) {
    const int nx = ext[b][0].second - ext[b][0].first + 1, ny = ext[b][1].second - ext[b][1].first + 1;
    EXPECT_EQ(nx * ny, blocks.start[b + 1] - blocks.start[b]) << "block " << b;
    EXPECT_TRUE(ext[b][0].first == 0 || ext[b][0].first == 2) << "block " << b;
  }
  // every element in exactly the block that lists it
  std::vector<int> count(size_t(quad.num_elements()), 0);
  for (int b = 0; b < 4; ++b)
    for (int k = blocks.start[b]; k < blocks.start[b + 1]; ++k) {
      ++count[size_t(blocks.elements[k])];
      EXPECT_EQ(blocks.block_of[size_t(blocks.elements[k])], b);
    }
  EXPECT_TRUE(std::all_of(count.begin(), count.end(), [](int c) { return c == 1; }));
}

TEST(PressureBlocks, ShortDirectionsAndPatchesKeepTheirOwnBlocks) {
  // a 3D box of 3 x 3 x 3 elements: one block of all 27 at width 2; a 2 x 2
  // square beside it in the displacement formulation (width 1): 4 blocks of one
  const Body cube(subdivide(elevate_to(box(1, 1, 1).patch, 2), 3));
  EXPECT_EQ(block_elements(BodyQuadrature(cube, 3), {2}).num_blocks(), 1);
  const Body two({square(4), square(2)}, {});
  const BodyQuadrature quad(two, 3);
  const ElementBlocks blocks = block_elements(quad, {2, 1});
  ASSERT_EQ(blocks.num_blocks(), 4 + 4);
  for (int b = 0; b < blocks.num_blocks(); ++b) {
    std::set<int> patches;
    for (int k = blocks.start[b]; k < blocks.start[b + 1]; ++k) patches.insert(quad.patch_of(blocks.elements[k]));
    EXPECT_EQ(patches.size(), 1U) << "block " << b << " crosses a patch boundary";
    EXPECT_EQ(blocks.start[b + 1] - blocks.start[b], b < 4 ? 4 : 1);
  }
  EXPECT_TRUE(block_elements(quad, {1}).per_element());
  const ElementBlocks mixed = mixed_pressure_blocks(quad, {Formulation::mixed, Formulation::displacement});
  EXPECT_EQ(mixed.block_of, blocks.block_of);
  EXPECT_TRUE(mixed_pressure_blocks(quad, {}).per_element());
  EXPECT_EQ(mixed_pressure_blocks(quad, {Formulation::mixed}).num_blocks(), 4 + 1);
  EXPECT_THROW(block_elements(quad, {2, 1, 1}), std::invalid_argument);
  EXPECT_THROW(block_elements(quad, {0}), std::invalid_argument);
}

TEST(PressureBlocks, PatternCouplesEveryControlPointOfABlockAndNothingMore) {
  const Body body(square(5));
  const BodyQuadrature quad(body, 3);
  const DofMap dofs(body, {DirichletCondition{{PatchSide(Face{0, false})}, 0, 0.0}});  // some dofs prescribed
  const ElementBlocks blocks = block_elements(quad, {2});
  const Eigen::SparseMatrix<double> pattern = coupling_pattern(quad, dofs, blocks);
  // brute force: equations couple when their control points share a block
  std::set<std::pair<int, int>> expected;
  std::vector<int> cps, all;
  for (int b = 0; b < blocks.num_blocks(); ++b) {
    all.clear();
    for (int k = blocks.start[b]; k < blocks.start[b + 1]; ++k) {
      quad.control_points(blocks.elements[k], cps);
      all.insert(all.end(), cps.begin(), cps.end());
    }
    for (int a : all)
      for (int c : all)
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j)
            if (dofs.equation(a * 2 + i) >= 0 && dofs.equation(c * 2 + j) >= 0)
              expected.insert({dofs.equation(a * 2 + i), dofs.equation(c * 2 + j)});
  }
  std::set<std::pair<int, int>> got;
  for (int c = 0; c < pattern.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(pattern, c); it; ++it) got.insert({int(it.row()), c});
  EXPECT_EQ(got, expected);
  EXPECT_GT(pattern.nonZeros(), coupling_pattern(quad, dofs).nonZeros());  // wider than the element pattern
  // blocks of one element: the element pattern itself
  const Eigen::SparseMatrix<double> one = coupling_pattern(quad, dofs, block_elements(quad, {1}));
  const Eigen::SparseMatrix<double> element = coupling_pattern(quad, dofs);
  ASSERT_EQ(one.nonZeros(), element.nonZeros());
  EXPECT_TRUE(std::equal(one.innerIndexPtr(), one.innerIndexPtr() + one.nonZeros(), element.innerIndexPtr()));
  // a range that splits a block is refused; one that cuts between blocks is not
  EXPECT_THROW(coupling_pattern(quad, dofs, blocks, 0, 1), std::logic_error);
}

TEST(PressureBlocks, BlocksOfOneColourShareNoEquation) {
  const Body body(square(6));
  const BodyQuadrature quad(body, 3);
  const DofMap dofs(body, {});
  const ElementBlocks blocks = block_elements(quad, {2});
  const auto colours = colour_blocks(quad, dofs, blocks);
  std::vector<int> seen(size_t(blocks.num_blocks()), 0);
  std::vector<int> cps;
  for (const auto& colour : colours) {
    std::set<int> written;
    for (int b : colour) {
      ++seen[size_t(b)];
      std::set<int> mine;
      for (int k = blocks.start[b]; k < blocks.start[b + 1]; ++k) {
        quad.control_points(blocks.elements[k], cps);
        mine.insert(cps.begin(), cps.end());
      }
      for (int a : mine) EXPECT_TRUE(written.insert(a).second) << "control point " << a << " written twice";
    }
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
  // 3 x 3 blocks of 2 x 2 quadratic elements (4 spans of control points each,
  // neighbours overlapping by 2): 2 colours per direction suffice
  EXPECT_EQ(colours.size(), 4U);
}

}  // namespace
}  // namespace igac
