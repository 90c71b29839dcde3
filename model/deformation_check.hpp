// SPDX-License-Identifier: BSD-3-Clause
// Whether a small-deformation result stayed within small deformation.
#pragma once

#include <optional>
#include <string>

#include "model/model.hpp"
#include "model/run_result.hpp"

namespace igac {

// The largest displacement beyond which a linear_elastic result is not to be
// trusted: 10 % of the body's size (the largest extent of its control net).
inline constexpr double kSmallDeformationLimit = 0.1;
// A warning (naming the case, by how much, and the large-deformation laws)
// when the small-deformation result `r` of `m` moves some point farther than
// kSmallDeformationLimit times the body's size; nullopt otherwise.
std::optional<std::string> small_deformation_warning(const Model& m, const RunResult& r);

}  // namespace igac
