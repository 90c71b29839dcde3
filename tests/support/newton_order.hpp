// SPDX-License-Identifier: BSD-3-Clause
// Newton's order of convergence read off a run's residual history: the one
// check of "quadratic once the active set settles" (one body, two bodies).
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "model/run_result.hpp"

namespace igac_test {

// r_{k+1} ~ C r_k^2: log r_{k+1} / log r_k >= min_order on the last pair of
// each step whose residuals lie between 1e-1 (asymptotic) and `floor`
// (above the round-off floor of |R|/F: ~1e-13 for one body, ~1e-11 for two
// bodies, whose slave-master blocks GMRES solves to about |R|); at least
// half the steps have one.
//
// Two bodies: the residual stalls near 1e-11 (measured: the roller on a
// block; the sliding block on an elastic block, plain Newton continued past
// convergence, between 4.5e-12 and 1.4e-11), so a last residual of 1.7e-11
// is that floor, not Newton's order: pairs are read above
// kTwoBodyRoundOffFloor there.
inline constexpr double kTwoBodyRoundOffFloor = 1e-9;
inline void expect_newton_order(const igac::RunResult& r, double min_order, double floor = 1e-11) {
  ASSERT_TRUE(r.load_steps.has_value());
  int pairs = 0;
  for (const auto& st : r.load_steps->steps) {
    const auto& n = st.residual_norms;
    for (int k = int(n.size()) - 1; k >= 1; --k) {
      if (n[k] < floor || n[k - 1] > 1e-1 || n[k - 1] < floor) continue;
      EXPECT_GE(std::log(n[k]) / std::log(n[k - 1]), min_order)
          << "step at t = " << st.load_factor << ": " << n[k - 1] << " -> " << n[k];
      ++pairs;
      break;
    }
  }
  EXPECT_GE(pairs, int(r.load_steps->steps.size()) / 2);
}

}  // namespace igac_test
