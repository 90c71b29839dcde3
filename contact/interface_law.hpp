// SPDX-License-Identifier: BSD-3-Clause
// The law of a contact interface: when a multiplier is closed, and what its
// tangential part does once it is.  A contact pair is a slave face, a
// partner (a rigid obstacle or a face of a body) and one of these laws; the
// solvers that may meet any law (contact/small_strain_friction.hpp,
// model/finite_strain_problem.hpp, finite_strain_friction.hpp) ask the
// pair's law per multiplier; the frictionless active-set loops, which only
// unilateral pairs reach (contact/small_strain_contact.hpp and the PETSc
// path through its next_active_set), call unilateral_closed below.  No
// solver writes a rule of its own.  The rules are stated on the complementarity values the
// primal-dual active set works with (Hueber, Stadler & Wohlmuth 2008):
//   normal      v = lambda_n + c_n g      (lambda_n <= 0 pushes; g the weighted gap)
//   tangential  xi = lambda_t + c_t s     (s the weighted slip over the step)
// and the Coulomb bound b = -f v (b <= 0: no tangential force).
//
// A law is one file in contact/laws/ and one line in the registry
// (contact/interface_law.cpp); a case names it with `[contact] law`.
#pragma once

#include <string>
#include <vector>

#include "contact/friction_state.hpp"

namespace igac {

// The two rules every unilateral law shares, written once.
// Closed where v < 0; within `tol` of zero (round-off of the larger of
// |lambda_n| and c_n |g|) the multiplier keeps its state `was`, so that at
// zero load nothing changes.  tol = 0: the strict rule.
bool unilateral_closed(double v, bool was, double tol = 0);
// Coulomb's cone: stick where |xi| <= b, slip beyond; on the cone to `tol`
// a closed multiplier keeps its state.
FrictionState coulomb_state(double xi_norm, double b, FrictionState was, double tol = 0);

class InterfaceLaw {
 public:
  virtual ~InterfaceLaw() = default;
  // The name a case file gives: "frictionless", "coulomb", "tied".
  virtual const char* name() const = 0;
  // Whether the pair carries tangential multipliers (rows T, lambda_t).
  virtual bool tangential() const = 0;
  // Whether the law takes a friction coefficient f > 0 (and needs one).
  virtual bool has_coefficient() const { return false; }
  // Whether multiplier K is closed (normal rule), its state `was`.
  virtual bool closed(double v, bool was, double tol) const { return unilateral_closed(v, was, tol); }
  // The tangential state of a closed multiplier: |xi|, its bound b (Coulomb,
  // from the coefficient f and v), its state `was`.  A law without
  // tangential rows slides (no tangential force).
  virtual FrictionState tangential_state(double xi_norm, double b, FrictionState was, double tol) const = 0;
  // Whether a closed multiplier may pull (lambda_n > 0): a bond.  Such a
  // law holds the gap the pair starts with (g - g_0 = 0) where a unilateral
  // one closes it (g = 0), and no "the load pulls the body off" check applies.
  virtual bool bilateral() const { return false; }
};

// The law of one pair: the law and its coefficient.  A coefficient alone
// names the default law (Coulomb where f > 0, else frictionless).
struct ContactLaw {
  const InterfaceLaw* law = nullptr;  // null: frictionless
  double friction = 0;                // Coulomb's f (InterfaceLaw::has_coefficient)
  ContactLaw() = default;
  ContactLaw(double f);  // NOLINT: a coefficient is its default law
  ContactLaw(const InterfaceLaw& l, double f) : law(&l), friction(f) {}
  const InterfaceLaw& get() const;
  bool tangential() const { return get().tangential(); }
};

// The law named `name`; throws std::invalid_argument naming the laws there are.
const InterfaceLaw& interface_law(const std::string& name);
std::vector<std::string> interface_law_names();
// The laws a pair takes without `law =`: Coulomb where f > 0, else frictionless.
const InterfaceLaw& default_interface_law(double friction);

// The laws of the registry, one file each (contact/laws/).
const InterfaceLaw& frictionless_law();
const InterfaceLaw& coulomb_law();
const InterfaceLaw& tied_law();

}  // namespace igac
