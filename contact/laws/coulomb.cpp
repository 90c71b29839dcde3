// SPDX-License-Identifier: BSD-3-Clause
// Coulomb friction: unilateral in the normal direction, and a closed
// multiplier sticks inside the cone |lambda_t| <= -f lambda_n and slips on it.
#include "contact/interface_law.hpp"

namespace igac {
namespace {
class Coulomb final : public InterfaceLaw {
 public:
  const char* name() const override { return "coulomb"; }
  bool tangential() const override { return true; }
  bool has_coefficient() const override { return true; }
  FrictionState tangential_state(double xi_norm, double b, FrictionState was, double tol) const override {
    return coulomb_state(xi_norm, b, was, tol);
  }
};
}  // namespace

const InterfaceLaw& coulomb_law() {
  static const Coulomb law;
  return law;
}

}  // namespace igac
