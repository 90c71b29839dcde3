// SPDX-License-Identifier: BSD-3-Clause
// Frictionless (unilateral) contact: a multiplier closes where it pushes,
// and slides freely once it does (no tangential rows).
#include "contact/interface_law.hpp"

namespace igac {
namespace {
class Frictionless final : public InterfaceLaw {
 public:
  const char* name() const override { return "frictionless"; }
  bool tangential() const override { return false; }
  FrictionState tangential_state(double, double, FrictionState, double) const override { return kSlip; }
};
}  // namespace

const InterfaceLaw& frictionless_law() {
  static const Frictionless law;
  return law;
}

}  // namespace igac
