// SPDX-License-Identifier: BSD-3-Clause
// What a frictional contact solve reports and carries between load steps,
// as data: the state of each multiplier and the slip history.  The solvers
// are contact/small_strain_friction.hpp and contact/finite_strain_friction.hpp;
// the outputs (io/) and the console (app/) read these without them.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace igac {

// Per multiplier: 0 open, 1 stick, 2 slip.
enum FrictionState : char { kOpen = 0, kStick = 1, kSlip = 2 };

// What a frictional solve carries from one step to the next: its slip
// history, as a restart reads it back from the step's state file
// (io/state_file.hpp), so that the steps after it are the ones a run that
// never stopped takes, bit for bit.
//   small deformation (SmallStrainFriction): the weighted tangential
//     position T u + t0 where the step ended, the accumulated slip, the
//     state, slip direction (m x nt, row-major) and b / |xi| of each
//     multiplier (the next step starts from them), and the Schur columns
//     computed so far, in the order and the batches they were computed in
//     (recomputed on restoring: the same columns, bit for bit);
//   large deformation (FiniteStrainFriction): the slip accumulated up to
//     the start of the step, and the time it started at (`from`); the rest
//     is recomputed from the converged state there.
struct FrictionHistory {
  Eigen::VectorXd position, slip, direction, alpha;
  std::vector<char> state;
  std::vector<std::vector<int>> schur_batches;
  double from = 0;
  bool empty() const { return slip.size() == 0 && state.empty(); }
};

}  // namespace igac
