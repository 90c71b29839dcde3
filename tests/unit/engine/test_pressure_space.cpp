// SPDX-License-Identifier: BSD-3-Clause
// The pressure space of the mixed formulation (engine/pressure_space.hpp):
// the sub-grid continuous space is a partition of unity on every element,
// its supports and the elements' function lists are transposes, and the
// pattern over its supports couples exactly the control points that share a
// function.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "engine/body.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/pressure_space.hpp"
#include "engine/sparsity.hpp"
#include "engine/spline/refinement.hpp"

namespace igac {
namespace {

NurbsPatch square(int degree, int parts) { return subdivide(elevate_to(rectangle(1, 1).patch, degree), parts); }

TEST(PressureSpace, SubGridSpaceIsAPartitionOfUnityWithTransposedSupports) {
  const Body body(square(3, 5));  // p = 3: quadratic C^1 pressure on spans of 2 and 3 elements
  const BodyQuadrature quad(body, 4);
  const PressureSpace space = mixed_pressure_space(quad, {Formulation::mixed});
  EXPECT_EQ(space.num_functions(), 4 * 4);  // 2 coarse spans + degree 2 per direction
  EXPECT_FALSE(space.per_element());
  EXPECT_FALSE(space.disjoint());
  ElementValues<2, 2> ev;
  PressureSpace::Scratch scratch;
  std::vector<double> v;
  for (int e = 0; e < quad.num_elements(); ++e) {
    EXPECT_EQ(space.num_element_functions(e), 9);
    quad.evaluate(e, ev, false);
    for (int q = 0; q < ev.n_q; ++q) {
      space.values(e, ev.xi[size_t(q)].data(), v, scratch);
      double sum = 0;
      for (double x : v) {
        EXPECT_GE(x, -1e-15);
        sum += x;
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
    }
    for (const int* a = space.functions_begin(e); a != space.functions_end(e); ++a)
      EXPECT_TRUE(std::binary_search(space.support_begin(*a), space.support_end(*a), e));
  }
  int entries = 0;
  for (int a = 0; a < space.num_functions(); ++a) entries += int(space.support_end(a) - space.support_begin(a));
  EXPECT_EQ(entries, 9 * quad.num_elements());
}

TEST(PressureSpace, ConstantsPerElementAreTheElementPattern) {
  const Body body(square(2, 4));
  const BodyQuadrature quad(body, 3);
  const PressureSpace space = mixed_pressure_space(quad, {Formulation::mixed_element});
  EXPECT_TRUE(space.per_element());
  EXPECT_EQ(space.num_functions(), quad.num_elements());
  const DofMap dofs(body, {});
  const Eigen::SparseMatrix<double> a = coupling_pattern(quad, dofs, space), b = coupling_pattern(quad, dofs);
  EXPECT_EQ(a.nonZeros(), b.nonZeros());
}

TEST(PressureSpace, PatternCouplesTheControlPointsOfEachSupport) {
  const Body body(square(2, 6));
  const BodyQuadrature quad(body, 3);
  const PressureSpace space = mixed_pressure_space(quad, {Formulation::mixed});
  const DofMap dofs(body, {});
  const Eigen::SparseMatrix<double> pattern = coupling_pattern(quad, dofs, space);
  std::set<std::pair<int, int>> expected;
  std::vector<int> cps, all;
  for (int a = 0; a < space.num_functions(); ++a) {
    all.clear();
    for (const int* e = space.support_begin(a); e != space.support_end(a); ++e) {
      quad.control_points(*e, cps);
      all.insert(all.end(), cps.begin(), cps.end());
    }
    for (int i : all)
      for (int j : all)
        for (int c = 0; c < 2; ++c)
          for (int d = 0; d < 2; ++d) expected.insert({2 * i + c, 2 * j + d});
  }
  EXPECT_EQ(pattern.nonZeros(), Eigen::Index(expected.size()));
  for (int k = 0; k < pattern.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(pattern, k); it; ++it)
      EXPECT_TRUE(expected.count({int(it.row()), int(it.col())}));
  // colours: no two functions of a colour share an equation
  for (const std::vector<int>& colour : colour_functions(quad, dofs, space)) {
    std::set<int> seen;
    for (int a : colour) {
      std::set<int> mine;
      for (const int* e = space.support_begin(a); e != space.support_end(a); ++e) {
        quad.control_points(*e, cps);
        mine.insert(cps.begin(), cps.end());
      }
      for (int i : mine) EXPECT_TRUE(seen.insert(i).second) << "function " << a << " shares control point " << i;
    }
  }
}

}  // namespace
}  // namespace igac
