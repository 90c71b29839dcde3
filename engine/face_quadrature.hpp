// SPDX-License-Identifier: BSD-3-Clause
// The one face loop of engine/ and contact/: Gauss quadrature over a list of
// sides of a body (a face of a multi-patch body may span several), tabulated
// once, that hands each face element's values (ElementValues<dim - 1, dim>: basis,
// parametric derivatives, points, weights, outward normals, body control
// points) to a visitor.  The follower and dead pressure
// (follower_pressure.cpp), the weighted gaps and the large-deformation
// contact (contact/weighted_gap.hpp, ContactQuadrature, which adds the
// multiplier basis at each point), the pressure report's L2 error and face
// samples (contact/pressure.cpp), and model/'s face integrals (the applied
// load's resultant, the mean face displacement, the deformed half width)
// go through it.
//
// The visitor is called as visit(int side, const ElementValues<dim - 1, dim>&
// values) per face element, sides in the given order and elements of a side
// in PatchQuadrature's order; the dimension is dispatched at run time, so a
// generic lambda (`const auto& values`) serves 2D and 3D.
#pragma once

#include <utility>
#include <vector>

#include "engine/body.hpp"
#include "engine/element_values.hpp"

namespace igac {

class FaceQuadrature {
 public:
  // `points` Gauss points per face direction on each side.
  FaceQuadrature(const Body& body, const std::vector<PatchSide>& sides, int points) {
    for (const PatchSide& s : sides) {
      sides_.push_back(s);
      quads_.push_back(body.side_quadrature(s, points));
    }
  }
  // Sides already as face quadratures (each made with its parent face).
  FaceQuadrature(std::vector<PatchSide> sides, std::vector<PatchQuadrature> quads)
      : sides_(std::move(sides)), quads_(std::move(quads)) {}

  int num_sides() const { return int(sides_.size()); }
  const PatchSide& side(int s) const { return sides_[s]; }
  int space_dim() const { return quads_.empty() ? 0 : quads_.front().patch().space_dim(); }

  template <class Visit>
  void for_each_element(Visit&& visit) const {
    if (space_dim() == 2)
      visit_elements<2>(visit);
    else if (space_dim() == 3)
      visit_elements<3>(visit);
  }

 private:
  template <int dim, class Visit>
  void visit_elements(Visit& visit) const {
    ElementValues<dim - 1, dim> v;
    for (int s = 0; s < num_sides(); ++s)
      for (int e = 0; e < quads_[s].num_elements(); ++e) {
        quads_[s].evaluate(e, v, false);
        visit(s, static_cast<const ElementValues<dim - 1, dim>&>(v));
      }
  }

  std::vector<PatchSide> sides_;
  std::vector<PatchQuadrature> quads_;
};

}  // namespace igac
