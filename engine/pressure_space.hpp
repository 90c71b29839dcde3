// SPDX-License-Identifier: BSD-3-Clause
// The pressure space of the mixed formulation: per patch, tensor-product
// B-splines on the patch's parameters, each with the elements of its support.
// The one definition every consumer uses (the assemblies, the u-p Newton's
// unknowns, the incompressible multipliers, the state file, the recovered
// pressure field), so a pressure number means the same function everywhere.
//
// Per patch, by formulation (mixed_pressure_space):
//   mixed          degree p_d - 1 in direction d, continuity C^{p_d - 2}, on
//                  breakpoints twice coarser than the displacement's (every
//                  kPressureCoarsening-th breakpoint; an odd leftover element
//                  joins the last span, so n = 5 gives spans of 2 and 3
//                  elements; fewer than 2 elements: one span).  The
//                  "sub-grid Taylor-Hood" pair of isogeometric Stokes
//                  (Bressan and Sangalli 2013): inf-sup stable, where the same
//                  space on the displacement's own breakpoints is not (beta_h
//                  falls like h, bench/inf_sup), and continuous, so the
//                  pressure has no staircase.  Displacement degree 1: degree 0.
//   mixed_element  degree 0 on the displacement's breakpoints: one constant
//                  per element (not uniformly inf-sup stable; the pair of
//                  before issue 24's blocks).
//   displacement   degree 0 per element too; such a patch carries no
//                  pressure, its functions are unused (and cost nothing).
// Functions never cross a patch boundary.  Numbering: patch after patch,
// first parametric direction fastest.  Elements are numbered as
// BodyQuadrature numbers them.  Degree-0 functions are indicators (value 1
// on their elements), so the continuous space and the constants are one code
// path everywhere.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "engine/discretisation.hpp"
#include "engine/spline/knot_vector.hpp"
#include "engine/volumetric_projection.hpp"

namespace igac {

class BodyQuadrature;

inline constexpr int kPressureCoarsening = 2;

class PressureSpace {
 public:
  PressureSpace() = default;
  // Per patch k: degree[k][d] >= 0 and the number of displacement elements
  // grouped into one pressure span, coarsening[k] >= 1 (one entry: every
  // patch's).  Throws std::invalid_argument for a negative degree, a
  // coarsening < 1 or lists of the wrong length.
  PressureSpace(const BodyQuadrature& quad, const std::vector<std::array<int, 3>>& degree,
                const std::vector<int>& coarsening);

  int num_functions() const { return int(start_.size()) - 1; }
  int num_elements() const { return int(element_start_.size()) - 1; }
  // Every function one element and every element one function (constants per
  // element: the element pattern and colouring serve).
  bool per_element() const { return per_element_; }
  // Every element in exactly one function (degree 0 everywhere): the supports
  // are disjoint blocks.
  bool disjoint() const { return disjoint_; }
  int patch_of_function(int a) const { return function_patch_[size_t(a)]; }

  // The support of function a: its elements, increasing.
  const int* support_begin(int a) const { return elements_.data() + start_[size_t(a)]; }
  const int* support_end(int a) const { return elements_.data() + start_[size_t(a) + 1]; }
  // The functions non-zero on element e, in the order of values().
  const int* functions_begin(int e) const { return functions_.data() + element_start_[size_t(e)]; }
  const int* functions_end(int e) const { return functions_.data() + element_start_[size_t(e) + 1]; }
  int num_element_functions(int e) const { return element_start_[size_t(e) + 1] - element_start_[size_t(e)]; }

  // The values of element e's functions at the patch parameters xi (its
  // first param_dim entries used): out[i] for functions_begin(e)[i].
  // `scratch` keeps the univariate tables between calls (one per thread).
  struct Scratch {
    std::array<std::array<double, 16>, 3> table{};  // univariate values per direction
    std::vector<double> point;                      // values_at's, one point's values
  };
  void values(int e, const double* xi, std::vector<double>& out, Scratch& scratch) const;
  // The same at each point of an element's list (ElementValues::xi, the
  // patch parameters of its Gauss points): N(q, i) for point q and function
  // functions_begin(e)[i]; resizes N.
  template <class Param>
  void values_at(int e, const std::vector<Param>& xi, Eigen::MatrixXd& N, Scratch& scratch) const {
    const int nf = num_element_functions(e);
    N.resize(Eigen::Index(xi.size()), nf);
    for (size_t q = 0; q < xi.size(); ++q) {
      values(e, xi[q].data(), scratch.point, scratch);
      for (int i = 0; i < nf; ++i) N(Eigen::Index(q), i) = scratch.point[size_t(i)];
    }
  }
  // The same at the element's local coordinates s in [0, 1]^param_dim (its
  // parameter box mapped linearly: a Bezier element's reference point).
  void values_local(int e, const double* s, std::vector<double>& out, Scratch& scratch) const;

 private:
  struct Patch {
    int param_dim = 0, first_function = 0;
    std::array<KnotVector, 3> knots;      // the pressure knots per direction
    std::array<int, 3> num{1, 1, 1};      // functions per direction
  };
  std::vector<Patch> patches_;
  std::vector<int> start_{0}, elements_;                 // function -> elements (CSR)
  std::vector<int> element_start_{0}, functions_;        // element -> functions (CSR)
  std::vector<int> element_patch_, function_patch_;
  std::vector<std::array<int, 3>> element_span_;         // the pressure knot span per direction
  std::vector<std::array<double, 6>> element_box_;       // parameter box: lo_d, hi_d
  bool per_element_ = true, disjoint_ = true;
};

// The mixed formulation's pressure space for patch_formulations (one entry:
// every patch's; empty: displacement everywhere), as the table above.
PressureSpace mixed_pressure_space(const BodyQuadrature& quad, const std::vector<Formulation>& patch_formulations);

}  // namespace igac
