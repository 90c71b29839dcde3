// SPDX-License-Identifier: BSD-3-Clause
#include "contact/interface_law.hpp"

#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <stdexcept>

namespace igac {

bool unilateral_closed(double v, bool was, double tol) {
  if (tol > 0 && std::abs(v) <= tol) return was;
  return v < 0;
}

FrictionState coulomb_state(double xi_norm, double b, FrictionState was, double tol) {
  if (tol > 0 && std::abs(xi_norm - b) <= tol && was != kOpen) return was;
  return xi_norm <= b ? kStick : kSlip;
}

namespace {
// The registry: one line per law.
using LawOf = const InterfaceLaw& (*)();
constexpr LawOf kLaws[] = {
    frictionless_law,
    coulomb_law,
    tied_law,
};
}  // namespace

std::vector<std::string> interface_law_names() {
  std::vector<std::string> out;
  for (LawOf law : kLaws) out.emplace_back(law().name());
  return out;
}

const InterfaceLaw& interface_law(const std::string& name) {
  for (LawOf law : kLaws)
    if (name == law().name()) return law();
  throw std::invalid_argument(fmt::format("{:?} is not an interface law (one of: {})", name,
                                          fmt::join(interface_law_names(), ", ")));
}

const InterfaceLaw& default_interface_law(double friction) {
  return friction > 0 ? coulomb_law() : frictionless_law();
}

ContactLaw::ContactLaw(double f) : law(&default_interface_law(f)), friction(f) {}

const InterfaceLaw& ContactLaw::get() const { return law ? *law : frictionless_law(); }

}  // namespace igac
