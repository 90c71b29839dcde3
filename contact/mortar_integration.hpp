// SPDX-License-Identifier: BSD-3-Clause
// How the mortar integral between two bodies is taken (contact/mortar_gap.hpp
// says what each does): a case names it with `[contact] integration`,
// resolved to this when the case is read.
#pragma once

#include <optional>
#include <string_view>

namespace igac {

enum class MortarIntegration { element, segmented };

inline std::optional<MortarIntegration> mortar_integration_named(std::string_view name) {
  if (name == "segmented") return MortarIntegration::segmented;
  if (name == "element") return MortarIntegration::element;
  return std::nullopt;
}

inline std::string_view name_of(MortarIntegration integration) {
  return integration == MortarIntegration::element ? "element" : "segmented";
}

}  // namespace igac
