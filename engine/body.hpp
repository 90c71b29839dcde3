// SPDX-License-Identifier: BSD-3-Clause
// A solid body made of NURBS patches joined C0 across conforming interfaces
// (the multi-patch discretisation of G+Smo and of Cottrell, Hughes and
// Bazilevs, Isogeometric Analysis, sec. 2.4): each patch keeps its own knots
// and control points, and the control points that two patches share on an
// interface carry one body number, hence one set of unknowns.  A one-patch
// body numbers its control points as the patch does.
//
// Conforming means: after refinement the two sides of an interface have the
// same degree, the same breakpoints (up to orientation and, in 3D, a swap of
// the two side directions) and coincident control points with equal weights.
// Then both sides are the same NURBS and the displacement is continuous.
// The engine matches the sides' control points geometrically (which also
// covers flipped and permuted parametrisations), so an interface needs no
// orientation data.
//
// BodyQuadrature is the element loop over every patch: element e of the body
// is an element of one patch, evaluated by that patch's PatchQuadrature with
// control points in body numbering, so assembly, error norms and stress
// recovery see one list of elements whatever the number of patches.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "engine/discretisation.hpp"
#include "engine/geometry/multipatch.hpp"

namespace igac {

// A body that cannot be assembled: a non-conforming interface, patches of
// different dimensions or degrees.  The message names the patches and sides.
class BodyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Body {
 public:
  Body() = default;
  // One patch, control points numbered as in the patch.  Implicit: every
  // function of the engine that takes a Body takes a lone patch as well.
  Body(NurbsPatch patch);  // NOLINT(google-explicit-constructor)
  // Patches joined across `interfaces` (an interface may join two sides of
  // one patch: the seam of a closed ring or tube).  Throws BodyError when the patches
  // differ in dimension, or an interface is not conforming (its sides differ
  // in degree, knots or points: naming both patches and sides and where).
  Body(std::vector<NurbsPatch> patches, const std::vector<PatchInterface>& interfaces);

  int num_patches() const { return int(patches_.size()); }
  const NurbsPatch& patch(int k) const { return patches_[k]; }
  const std::vector<NurbsPatch>& patches() const { return patches_; }
  const std::vector<PatchInterface>& interfaces() const { return interfaces_; }
  // Body number of each control point of patch k.
  const std::vector<int>& body_cps(int k) const { return body_cps_[k]; }
  int num_control_points() const { return num_cps_; }
  // Body control point coordinates and weights (one row per body number).
  const Eigen::MatrixXd& points() const { return points_; }
  int space_dim() const { return patches_.empty() ? 0 : patches_[0].space_dim(); }
  int param_dim() const { return patches_.empty() ? 0 : patches_[0].param_dim(); }
  int degree() const { return degree_; }  // the largest degree of any direction of any patch
  int num_elements() const;
  // One patch with no side joined to another: body numbers are patch numbers.
  bool numbered_as_patch() const { return patches_.size() == 1 && interfaces_.empty(); }

  // Body numbers of a side's control points, in the side's own numbering
  // (that of NurbsPatch::face_patch).  Throws BodyError for a side that does
  // not exist.
  std::vector<int> side_control_points(const PatchSide& s) const;
  NurbsPatch side_patch(const PatchSide& s) const;
  // Gauss quadrature of a side (outward normals), control points in body numbering.
  PatchQuadrature side_quadrature(const PatchSide& s, int points) const;
  // The patch's displacement coefficients (one row per patch control point)
  // from body coefficients (one row per body control point).
  Eigen::MatrixXd patch_field(int k, const Eigen::MatrixXd& body_field) const;
  // "patch 1 (east)"
  std::string describe(const PatchSide& s) const;
  // The separate bodies: part[k] is the same for patches k that interfaces
  // join, directly or through others (the smallest patch number among them).
  std::vector<int> parts() const;

 private:
  std::vector<NurbsPatch> patches_;
  std::vector<PatchInterface> interfaces_;
  std::vector<std::vector<int>> body_cps_;
  Eigen::MatrixXd points_;
  int num_cps_ = 0, degree_ = 0;
};

// Gauss quadrature over every element of every patch of a body (the
// FEValues role for a whole body): elements numbered patch by patch.
class BodyQuadrature {
 public:
  BodyQuadrature(const Body& body, int points);
  int num_elements() const { return first_.back(); }
  // Largest number of local functions of an element.
  int num_local() const { return num_local_; }
  int num_patches() const { return int(patches_.size()); }
  int patch_of(int e) const;
  const PatchQuadrature& patch_quadrature(int k) const { return patches_[k]; }
  int first_element(int k) const { return first_[k]; }
  void evaluate(int e, ElementData& out, bool gradients) const;
  template <int pd, int sd>
  void evaluate(int e, ElementValues<pd, sd>& out, bool gradients) const {
    const int k = patches_.size() == 1 ? 0 : patch_of(e);
    patches_[k].evaluate(e - first_[k], out, gradients);
  }
  void control_points(int e, std::vector<int>& cps) const;

 private:
  std::vector<PatchQuadrature> patches_;
  std::vector<int> first_{0};
  int num_local_ = 0;
};

}  // namespace igac
