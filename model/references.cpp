// SPDX-License-Identifier: BSD-3-Clause
#include "model/references.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace igac {
namespace {

// The (E, nu) that turn a plane-strain closed form into the case's: its own
// in plane strain (and 3D); in plane stress E (1 + 2 nu) / (1 + nu)^2 and
// nu / (1 + nu), whose plane-strain Lame constants are plane stress's
// (lambda* = 2 lambda mu / (lambda + 2 mu), mu).  Hertz's E / (1 - nu^2)
// then reads E, the plane stress contact modulus.
std::pair<double, double> in_plane_constants(const CaseSpec& spec) {
  if (!spec.plane_stress()) return {spec.E, spec.nu};
  const double nu = spec.nu;
  return {spec.E * (1 + 2 * nu) / ((1 + nu) * (1 + nu)), nu / (1 + nu)};
}

// Hertz: a round body of radius R (a quarter disc in 2D, a sphere octant in
// 3D, or a geometry file that gives its radius; an axisymmetric quarter disc
// is a hemisphere, the sphere's closed form) pressed by the sum P of its
// pressure loads onto one rigid plane (contact/pressure.hpp has the formulas).
std::string hertz_unusable(const CaseSpec& c) {
  const bool round = c.shape == "quarter_disc" || c.shape == "sphere_octant" || (c.shape == "file" && c.radius > 0);
  if (c.contacts.size() != 1 || !round)
    return "hertz needs a quarter_disc or sphere_octant (or a geometry file with its radius) with one [contact]";
  return {};
}

std::optional<HertzSolution> hertz_pressure(const CaseSpec& spec) {
  double P = 0;
  for (const auto& p : spec.pressure) P += p.value;
  const auto [E, nu] = in_plane_constants(spec);
  return spec.dim() == 2 && !spec.axisymmetric() ? hertz_cylinder(spec.radius, P, E, nu)
                                                 : hertz_sphere(spec.radius, P, E, nu);
}

std::optional<ExactDisplacement> no_displacement(const CaseSpec&) { return std::nullopt; }
std::optional<HertzSolution> no_pressure(const CaseSpec&) { return std::nullopt; }

// Lame: the thick cylinder (plane strain), disc (plane stress) or sphere (axisymmetric) (a quarter annulus, or a geometry
// file that gives both radii) under the pressure on its face "inner".
std::string lame_unusable(const CaseSpec& c) {
  if (c.shape != "quarter_annulus" && !(c.shape == "file" && c.inner_radius > 0 && c.outer_radius > 0))
    return "lame needs shape = \"quarter_annulus\" (or a geometry file with inner_radius and outer_radius)";
  return {};
}

// A radial displacement u_r(r) about the origin as a field of the plane (of
// the r-z section in the axisymmetric model, where r = |X| is the sphere's
// radius): u = u_r e_r, grad u = u_r' e_r e_r^T + (u_r / r) e_t e_t^T.
// radial(r) gives (u_r, u_r').
template <class Radial>
ExactDisplacement radial_displacement(Radial radial) {
  return [=](const Eigen::VectorXd& X, Eigen::VectorXd& u, Eigen::MatrixXd& g) {
    const double r = std::hypot(X[0], X[1]);
    const auto [ur, dur] = radial(r);
    const double ct = X[0] / r, st = X[1] / r;
    u.resize(2);
    u << ur * ct, ur * st;
    g.resize(2, 2);
    g << dur * ct * ct + ur / r * st * st, (dur - ur / r) * ct * st, (dur - ur / r) * ct * st,
        dur * st * st + ur / r * ct * ct;
  };
}

std::optional<ExactDisplacement> lame_displacement(const CaseSpec& spec) {
  double pi = 0;
  for (const auto& p : spec.pressure)
    for (const auto& f : p.faces)
      if (f == "inner") pi += p.value;
  const auto [E, nu] = in_plane_constants(spec);
  const double a = spec.inner_radius, b = spec.outer_radius;
  if (spec.axisymmetric()) {
    // The thick sphere (an axisymmetric quarter annulus: the half shell
    // x >= 0 about the y axis, held at y = 0 by symmetry), internal
    // pressure pi on r = a (Timoshenko & Goodier, sec. 141):
    // u_r = pi a^3 / (E (b^3 - a^3)) ((1 - 2 nu) r + (1 + nu) b^3 / (2 r^2)).
    const double c = pi * a * a * a / (E * (b * b * b - a * a * a)), b3 = b * b * b;
    return radial_displacement([=](double r) {
      return std::pair{c * ((1 - 2 * nu) * r + (1 + nu) * b3 / (2 * r * r)), c * ((1 - 2 * nu) - (1 + nu) * b3 / (r * r * r))};
    });
  }
  // Plane strain thick cylinder (plane stress: in_plane_constants), internal pressure pi on r = a, free at r = b:
  // sigma_rr = A - B/r^2, A = pi a^2/(b^2-a^2), B = pi a^2 b^2/(b^2-a^2),
  // u_r = (1+nu)/E ((1-2nu) A r + B/r).
  const double A = pi * a * a / (b * b - a * a), B = pi * a * a * b * b / (b * b - a * a);
  const double c = (1 + nu) / E;
  return radial_displacement([=](double r) {
    return std::pair{c * ((1 - 2 * nu) * A * r + B / r), c * ((1 - 2 * nu) * A - B / (r * r))};
  });
}

const ReferenceSolution kReferences[] = {
    {"hertz", hertz_unusable, no_displacement, hertz_pressure},
    {"lame", lame_unusable, lame_displacement, no_pressure},
};

}  // namespace

const ReferenceSolution* find_reference(std::string_view name) {
  for (const ReferenceSolution& r : kReferences)
    if (r.name == name) return &r;
  return nullptr;
}

std::vector<std::string_view> reference_names() {
  std::vector<std::string_view> out;
  for (const ReferenceSolution& r : kReferences) out.push_back(r.name);
  out.push_back("none");
  return out;
}

std::optional<ExactDisplacement> exact_displacement(const CaseSpec& spec) {
  const ReferenceSolution* ref = find_reference(spec.reference);
  return ref ? ref->displacement(spec) : std::nullopt;
}

void compare_with_reference(const Model& m, RunResult& r) {
  const ReferenceSolution* ref = find_reference(m.spec.reference);
  if (!ref) return;
  const Body& body = m.body;
  if (r.contacts.size() == 1 && r.contacts.front().pressure)  // Hertz: one contact
    if (const auto h = ref->contact_pressure(m.spec)) {
      r.hertz = *h;
      const ContactPressure& cp = *r.contacts.front().pressure;
      r.pressure_error = cp.l2_error(
          *m.contacts.front().face,
          [&](int, const Eigen::VectorXd&, const Eigen::VectorXd& X) { return h->pressure(cp.r_of(X)); },
          std::max(10, body.degree() + 1));
    }
  if (!m.spec.finite_strain())
    if (const auto exact = ref->displacement(m.spec))
      r.displacement_errors = errors_against_exact(body, r.u, *exact, body.degree() + 2);
}

}  // namespace igac
