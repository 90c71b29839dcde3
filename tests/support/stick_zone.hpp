// SPDX-License-Identifier: BSD-3-Clause
// The stick zone of a 2D frictional contact (Cattaneo-Mindlin tests against
// a rigid plane and between two bodies), read from the multipliers' states,
// the stuck multipliers' slip, and a 3D face dragged until it slides.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "contact/small_strain_friction.hpp"
#include "contact/weighted_gap.hpp"
#include "model/run_result.hpp"

namespace igac_test {

struct StickZone {
  double half_width = 0;    // of the stuck multipliers, to their elements' edges
  double spacing = 0;       // the largest distance between neighbouring anchors in the contact zone
  double zone_half_width = 0;  // of the closed (stick or slip) multipliers' anchors
  int stuck = 0;
};

// Half the extent in x of the stuck multipliers' anchors, plus half a
// spacing (degree 2: each multiplier is constant on its element, its anchor
// the element's middle); the spacing: the largest distance between the
// anchors of neighbouring multipliers of the zone.
inline StickZone stick_zone(const igac::ContactFace& face, const std::vector<char>& state) {
  std::vector<double> stick_x, zone_x;
  for (const igac::ContactSide& side : face.sides)
    for (int k = 0; k < side.space.size(); ++k) {
      const int K = side.first_multiplier + k;
      const double x = side.face_patch.point(side.space.anchor(k))[0];
      if (state[K] != igac::kOpen) zone_x.push_back(x);
      if (state[K] == igac::kStick) stick_x.push_back(x);
    }
  StickZone z;
  z.stuck = int(stick_x.size());
  if (stick_x.empty() || zone_x.size() < 2) return z;
  std::sort(zone_x.begin(), zone_x.end());
  for (size_t i = 1; i < zone_x.size(); ++i) z.spacing = std::max(z.spacing, zone_x[i] - zone_x[i - 1]);
  const auto [lo, hi] = std::minmax_element(stick_x.begin(), stick_x.end());
  z.half_width = 0.5 * (*hi - *lo) + 0.5 * z.spacing;
  z.zone_half_width = 0.5 * (zone_x.back() - zone_x.front());
  return z;
}

// How many multipliers stick; each of them has not slipped: |slip| <= tolerance.
inline int stuck_without_slip(const igac::ContactSolution& s, double tolerance) {
  int stuck = 0;
  for (size_t K = 0; K < s.friction_state.size(); ++K)
    if (s.friction_state[K] == igac::kStick) {
      ++stuck;
      EXPECT_LE(std::abs(s.slip[Eigen::Index(K)]), tolerance) << "multiplier " << K;
    }
  return stuck;
}

// A 3D face dragged along (3, 4, 0) until it slides: every multiplier slips
// on the disc |lambda_t| = -f lambda_n (to round_off of the largest
// pressure); the tangential force is f N along (0.6, 0.8) to `direction`,
// its size f N to `size` relative, from below (each multiplier slides along
// its own slip, which the body's elastic shear makes vary over the face).
inline void expect_sliding_on_the_disc(const igac::ContactSolution& s, const igac::ObstacleReaction& r, double f,
                                       double round_off, double direction, double size) {
  for (size_t K = 0; K < s.friction_state.size(); ++K) {
    EXPECT_EQ(s.friction_state[K], igac::kSlip) << "multiplier " << K;
    EXPECT_NEAR(s.lambda_t.segment(2 * Eigen::Index(K), 2).norm(), -f * s.lambda[Eigen::Index(K)],
                round_off * -s.lambda.minCoeff());
  }
  ASSERT_EQ(r.tangential_force.size(), 2);
  EXPECT_LE(r.tangential_force.norm(), f * r.normal_force * (1 + round_off));
  EXPECT_GE(r.tangential_force.norm(), f * r.normal_force * (1 - size));
  EXPECT_NEAR(r.tangential_force[0] / r.tangential_force.norm(), 0.6, direction);
  EXPECT_NEAR(r.tangential_force[1] / r.tangential_force.norm(), 0.8, direction);
}

}  // namespace igac_test
