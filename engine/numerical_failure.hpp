// SPDX-License-Identifier: BSD-3-Clause
// The one exception the Newton driver (engine/load_stepping.hpp) treats as
// an expected outcome: a trial state the problem cannot evaluate (a contact
// point at the centre of a rigid sphere, where the obstacle has no normal),
// thrown from inside a residual or Jacobian.  The load step fails with its
// message and is cut back, as when the problem returns false (det F <= 0).
//
// Anything else thrown there — std::logic_error and its kin (a bug: an index
// out of range, a size mismatch), std::bad_alloc, a solver's runtime_error —
// is not a property of the trial state: the driver carries it across
// KINSOL's C frames and rethrows it, so a bug ends the program as one
// instead of turning into a "failed" run.
#pragma once

#include <stdexcept>
#include <string>

namespace igac {

class NumericalFailure : public std::runtime_error {
 public:
  explicit NumericalFailure(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace igac
