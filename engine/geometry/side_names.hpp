// SPDX-License-Identifier: BSD-3-Clause
// The parametric names of the sides of a body of `patches` patches with
// `param_dim` parametric directions: "PATCH:SIDE" with SIDE one of G+Smo's
// west east south north front back or u0 u1 v0 v1 w0 w1, and on a one-patch
// body u0 ... w1 alone.  Shared by the built-in shapes and the case's body.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/geometry/multipatch.hpp"

namespace igac {

std::optional<PatchSide> parametric_side(const std::string& name, int patches, int param_dim);
// Every such name, for error messages (PATCH:u0 forms left out).
std::vector<std::string> parametric_side_names(int patches, int param_dim);

}  // namespace igac
