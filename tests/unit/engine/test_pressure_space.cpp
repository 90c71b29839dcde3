// SPDX-License-Identifier: BSD-3-Clause
// The pressure space of the mixed formulation (engine/pressure_space.hpp):
// the sub-grid continuous space is a partition of unity on every element,
// its supports and the elements' function lists are transposes, and the
// pattern over its supports couples exactly the control points that share a
// function.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
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

// m_A = int N_A dX, the lumped pressure mass, summed over the elements of
// A's support only, is the B-spline's integral (t_{i+q+1} - t_i) / (q + 1)
// per direction (the unit square's map is the identity on [0, 1]^2): the
// support lists hold every element where A is non-zero, and values() order
// matches functions_begin().  The masses sum to the area.
TEST(PressureSpace, FunctionIntegralOverItsSupportIsTheBSplineIntegral) {
  const Body body(square(3, 7));  // quadratic C^1 pressure on spans of 2, 2 and 3 elements
  const BodyQuadrature quad(body, 4);
  const PressureSpace space = mixed_pressure_space(quad, {Formulation::mixed});
  // the pressure knots: every second breakpoint of 0, 1/7, ..., 1, the odd one left out
  const std::vector<double> t = {0, 0, 0, 2.0 / 7, 4.0 / 7, 1, 1, 1};
  ASSERT_EQ(space.num_functions(), 5 * 5);
  ElementValues<2, 2> ev;
  PressureSpace::Scratch scratch;
  std::vector<double> v;
  double total = 0;
  for (int a = 0; a < space.num_functions(); ++a) {
    double m = 0;
    for (const int* e = space.support_begin(a); e != space.support_end(a); ++e) {
      quad.evaluate(*e, ev, false);
      const int i = int(std::find(space.functions_begin(*e), space.functions_end(*e), a) - space.functions_begin(*e));
      ASSERT_LT(i, space.num_element_functions(*e));
      for (int q = 0; q < ev.n_q; ++q) {
        space.values(*e, ev.xi[size_t(q)].data(), v, scratch);
        m += v[size_t(i)] * ev.JxW[q];
      }
    }
    const int i0 = a % 5, i1 = a / 5;  // first parametric direction fastest
    const double exact = (t[size_t(i0) + 3] - t[size_t(i0)]) / 3 * (t[size_t(i1) + 3] - t[size_t(i1)]) / 3;
    EXPECT_NEAR(m, exact, 1e-14) << "function " << a;
    total += m;
  }
  EXPECT_NEAR(total, 1.0, 1e-14);
}

// values_local at an element's corner s in {0, 1}^2 is values() at its
// parameter corner, and the sub-grid space is continuous: at a corner that
// elements share, each function of both takes one value, and a function of
// only one of them vanishes there.
TEST(PressureSpace, LocalCornerValuesAreTheParameterCornerValuesAndAgreeAcrossElements) {
  const Body body(square(2, 5));  // linear C^0 pressure on spans of 2 and 3 elements
  const BodyQuadrature quad(body, 3);
  const PressureSpace space = mixed_pressure_space(quad, {Formulation::mixed});
  const PatchQuadrature& pq = quad.patch_quadrature(0);
  const std::vector<double> bp = pq.patch().knots(0).breakpoints();
  ASSERT_EQ(bp.size(), 6u);
  PressureSpace::Scratch scratch;
  std::vector<double> local, at_xi;
  std::map<std::pair<int, int>, std::map<int, double>> at_vertex;  // breakpoint pair -> function -> value
  for (int e = 0; e < quad.num_elements(); ++e) {
    const std::array<int, 3> ei = pq.element_index(e);
    for (int c = 0; c < 4; ++c) {
      const int c0 = c % 2, c1 = c / 2;
      const double s[2] = {double(c0), double(c1)};
      const double xi[2] = {bp[size_t(ei[0] + c0)], bp[size_t(ei[1] + c1)]};
      space.values_local(e, s, local, scratch);
      space.values(e, xi, at_xi, scratch);
      ASSERT_EQ(local.size(), at_xi.size());
      for (size_t i = 0; i < local.size(); ++i) EXPECT_NEAR(local[i], at_xi[i], 1e-15);
      std::map<int, double>& seen = at_vertex[{ei[0] + c0, ei[1] + c1}];
      const int* fa = space.functions_begin(e);
      for (size_t i = 0; i < local.size(); ++i) {
        const auto [it, fresh] = seen.emplace(fa[i], local[i]);
        if (!fresh) {
          EXPECT_NEAR(it->second, local[i], 1e-15) << "function " << fa[i] << " element " << e;
        }
      }
    }
  }
  // a function seen at a vertex from one element only is zero there (its support ends at that vertex)
  for (const auto& [vertex, values] : at_vertex)
    for (const auto& [a, value] : values) {
      int holders = 0;
      for (const int* e = space.support_begin(a); e != space.support_end(a); ++e) {
        const std::array<int, 3> ei = pq.element_index(*e);
        holders += (vertex.first == ei[0] || vertex.first == ei[0] + 1) && (vertex.second == ei[1] || vertex.second == ei[1] + 1);
      }
      const int sharing = (vertex.first > 0 && vertex.first < 5 ? 2 : 1) * (vertex.second > 0 && vertex.second < 5 ? 2 : 1);
      if (holders < sharing) {
        EXPECT_NEAR(value, 0.0, 1e-15) << "function " << a;
      }
    }
}

}  // namespace
}  // namespace igac
