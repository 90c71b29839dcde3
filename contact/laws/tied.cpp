// SPDX-License-Identifier: BSD-3-Clause
// Tied (bonded) contact: two faces glued where they stand at the start,
// whatever their meshes (assemblies, non-conforming patches).  Every
// multiplier is closed and stuck from the start: the weighted gap keeps
// its initial value (g - g_0 = 0, the normal multiplier may pull) and the
// weighted slip is zero (the tangential one is unbounded): the mortar tie
// of the two faces' displacements, in both kinematics.
#include "contact/interface_law.hpp"

namespace igac {
namespace {
class Tied final : public InterfaceLaw {
 public:
  const char* name() const override { return "tied"; }
  bool tangential() const override { return true; }
  bool closed(double, bool, double) const override { return true; }
  FrictionState tangential_state(double, double, FrictionState, double) const override { return kStick; }
  bool bilateral() const override { return true; }
};
}  // namespace

const InterfaceLaw& tied_law() {
  static const Tied law;
  return law;
}

}  // namespace igac
