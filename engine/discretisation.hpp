// SPDX-License-Identifier: BSD-3-Clause
// The quadrature of a patch (or of a face of it): univariate B-spline values
// tabulated once per direction at the Gauss points, so an element evaluation
// only forms tensor products.  PatchQuadrature::evaluate into an
// ElementValues (element_values.hpp, sizes fixed at compile time) is the one
// element kernel of igac; ElementData is the same values in run-time-sized
// matrices, copied from it, for callers that do not know the dimension.
// PatchQuadrature::control_points is the one map from an element to its
// control points.
//
// Volume patches (param_dim == space_dim): dN/dX = dN/dxi J^{-1},
// JxW = det J * w.  Face patches (param_dim == space_dim - 1): the outward
// area vector s cof(J) e_d gives the unit normal and dGamma = |n dA| w.
// On a revolved patch (nurbs_patch.hpp, the axisymmetric model) both also
// carry 2 pi r: integrals are over the whole solid of revolution.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "engine/element_values.hpp"
#include "engine/quadrature.hpp"
#include "engine/spline/nurbs_patch.hpp"

namespace igac {

// Values of the degree+1 B-splines of one direction at the Gauss points of
// every element of that direction.
struct UnivariateTable {
  int degree = 0;
  int n_points = 0;
  std::vector<int> span;        // per element
  std::vector<double> xi;       // [e * n_points + q]
  std::vector<double> weight;   // Gauss weight times element length
  std::vector<double> value;    // [(e * n_points + q) * (degree+1) + j]
  std::vector<double> deriv;
};
UnivariateTable tabulate(const KnotVector& kv, const GaussRule& rule);

struct ElementData {
  std::vector<int> cps;              // control points (parent numbering)
  Eigen::MatrixXd N;                 // n_q x n_loc
  std::vector<Eigen::MatrixXd> dN;   // per q: n_loc x space_dim (volume only)
  Eigen::MatrixXd X;                 // n_q x space_dim
  Eigen::MatrixXd xi;                // n_q x param_dim
  Eigen::VectorXd JxW;               // n_q
  Eigen::MatrixXd normal;            // n_q x space_dim, unit outward (faces only)
  double min_det_J = 0;              // volume: smallest det J at the points
  bool revolved = false;             // axisymmetric (ElementValues::revolved)
};

class PatchQuadrature {
 public:
  // Gauss rule with `points` per direction.  For a face patch pass the face
  // (of the parent) and the parent's control point numbers of the face.
  PatchQuadrature(const NurbsPatch& patch, int points, std::optional<Face> face = {},
                  std::vector<int> parent_cps = {});

  int num_elements() const { return n_el_[0] * n_el_[1] * n_el_[2]; }
  int num_points() const;
  int num_local() const;
  std::array<int, 3> element_index(int e) const;
  // Elements (non-empty knot spans) per parametric direction; 1 past param_dim.
  const std::array<int, 3>& elements_per_direction() const { return n_el_; }
  const NurbsPatch& patch() const { return patch_; }
  // Fills `out` for element e; gradients only when asked (volume patches).
  // The fixed-size form needs pd = param_dim and sd = space_dim of the patch
  // (instantiated for volumes and faces in 2D and 3D).
  template <int pd, int sd>
  void evaluate(int e, ElementValues<pd, sd>& out, bool gradients) const;
  void evaluate(int e, ElementData& out, bool gradients) const;
  // Control points (parent numbering) of element e, local functions first
  // direction fastest; with `own`, also their numbers in the patch.
  void control_points(int e, std::vector<int>& cps, std::vector<int>* own = nullptr) const;

 private:
  NurbsPatch patch_;
  std::optional<Face> face_;
  std::vector<int> parent_cps_;
  std::array<UnivariateTable, 3> tables_;
  std::array<int, 3> n_el_{1, 1, 1};
};

}  // namespace igac
