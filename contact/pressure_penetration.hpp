// SPDX-License-Identifier: BSD-3-Clause
// Pressure penetration: a fluid pressure that acts on a face only where the
// fluid reaches it, from an entry point along the face and no further than
// where the face is pressed against a partner (the seal's contact band
// stops it).  Abaqus calls it *PRESSURE PENETRATION; FEBio's fluid pressure
// load is the same idea.
//
// The loaded faces are cut into their face elements (the elements of each
// side in PatchQuadrature's order).  An element is pressed when a contact
// on that side carries a compressive resultant over it,
//   int_e -lambda_h dGamma_0 > 0,   lambda_h = sum_K lambda_K B_K
// (multipliers negative in compression, contact/weighted_gap.hpp): with
// p = 2 (piecewise constant multipliers) exactly when the element's
// multiplier is active.  The wet elements are those reached from the entry
// element (the one nearest the entry point) through elements that are not
// pressed, across element and side boundaries (elements meet where they
// share a corner in 2D, an edge in 3D).  The front therefore moves element
// by element with the contact band; the driver settles it by solving a
// load step again while the wet set changes (FiniteStrainProblem::augment).
//
// Owner: contact/.  The follower and dead pressure loads
// (engine/follower_pressure.hpp) take the wet set as a mask.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "contact/weighted_gap.hpp"
#include "engine/body.hpp"
#include "engine/follower_pressure.hpp"  // FaceElementFlags

namespace igac {

class FluidFront {
 public:
  // `faces`: the sides the pressure is given on; `entry`: a point (reference
  // configuration) at or near where the fluid enters.  Throws
  // std::invalid_argument for no faces or an entry of the wrong dimension.
  FluidFront(const Body& body, std::vector<PatchSide> faces, const Eigen::VectorXd& entry);
  const std::vector<PatchSide>& faces() const { return faces_; }
  // Nothing pressed (every element false), sized as the faces' elements.
  FaceElementFlags none() const;
  // The wet elements when `pressed` are pressed (none wet if the entry
  // element itself is).
  FaceElementFlags wet(const FaceElementFlags& pressed) const;
  // Where the fluid enters: side and element.
  int entry_side() const { return entry_side_; }
  int entry_element() const { return entry_element_; }

 private:
  std::vector<PatchSide> faces_;
  std::vector<int> first_;                    // node number of each side's first element (and the total, last)
  std::vector<std::vector<int>> neighbours_;  // per node (side s, element e: first_[s] + e)
  int entry_side_ = 0, entry_element_ = 0;
};

// Marks in `pressed` the elements of `front`'s faces that contact face `cf`
// presses with the multipliers `lambda` (cf's own numbering): each side of
// cf that is one of the front's faces, element by element.
void mark_pressed(const FluidFront& front, const ContactFace& cf, const Eigen::VectorXd& lambda,
                  FaceElementFlags& pressed);

}  // namespace igac
