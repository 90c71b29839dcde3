// SPDX-License-Identifier: BSD-3-Clause
// Contact pressure p = -lambda (>= 0) after a solve, and its comparison with
// Hertz (Johnson, Contact Mechanics, ch. 4; docs/design.md, "Reference solutions"):
//   2D (force per unit length F' = 2 R P): a = sqrt(8 R^2 P (1-nu^2) / (pi E)),
//       p0 = 4 R P / (pi a);
//   3D (F = pi R^2 P): a = (3 pi R^3 P (1-nu^2) / (4 E))^(1/3), p0 = 3 R^2 P / (2 a^2);
//   p(r) = p0 sqrt(1 - r^2/a^2) for r < a, 0 beyond.
// r is the distance from the initial contact point X0 measured along the
// obstacle (orthogonal to its normal at X0).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "contact/weighted_gap.hpp"

namespace igac {

struct HertzSolution {
  double a = 0, p0 = 0;
  double pressure(double r) const;
};
HertzSolution hertz_cylinder(double R, double P, double E, double nu);  // 2D
HertzSolution hertz_sphere(double R, double P, double E, double nu);    // 3D

struct PressureSample {
  double r = 0, pressure = 0;
};

struct PressureReport {
  std::vector<PressureSample> multipliers;   // per multiplier: anchor and -lambda_K
  std::vector<PressureSample> p1;            // P1 re-interpolation along the profile edge
  double max_pressure = 0;                   // max_K -lambda_K
  double total_force = 0;                    // sum_K -lambda_K K_K
  // The contact edge in r, interpolated from the pressure (ContactPressure::edge_along):
  // along the face edge that starts at X0 when X0 is a corner of a side (a
  // symmetry plane through it); where X0 lies inside a side, the mean of the
  // edges along each parametric direction through it, both ways.
  double half_width = 0;
  int active = 0;
};

class ContactPressure {
 public:
  // X0: the initial contact point; normal: the obstacle normal there.
  // The face `cf` must outlive the object.
  ContactPressure(const ContactFace& cf, Eigen::VectorXd lambda, Eigen::VectorXd weights, std::vector<char> active,
                  Eigen::VectorXd X0, Eigen::VectorXd normal);
  double r_of(const Eigen::VectorXd& X) const;
  // p_h at parameter xi of side `side` of the face.
  double pressure_at(int side, const Eigen::VectorXd& xi) const;
  PressureReport report() const;
  // The contact edge r = a along the parameter line t -> line(t) of side
  // `side`, walked outward through b (b[0] its start, then breakpoints):
  // where the elliptic pressure of a smooth contact, p = c sqrt(a^2 - r^2)
  // (Hertz's shape; near any smooth edge c' sqrt(a - r)), fitted to the
  // pressure near the edge, vanishes.  Continuous multipliers (S1 and up):
  // p^2 linear in r^2 through the last two pressed nodal values, within the
  // element that follows them.  S0: the element means of sqrt(a^2 - r^2)
  // over the last two pressed elements in the ratio of their multipliers
  // (bisection).  The end of the
  // line where it is pressed throughout (at_end_of_side); r = 0 where
  // nothing along it is.
  struct Edge {
    double r = 0;
    bool at_end_of_side = false;
  };
  Edge edge_along(int side, const std::function<Eigen::VectorXd(double)>& line, const std::vector<double>& b,
                  double max_pressure) const;
  // || p_h - p ||_{L2(Gamma_C)} and || p ||, p given as a function of the side,
  // its parameter and the physical point, integrated with `points` Gauss points per
  // face element direction of `mesh` (a face of the same geometry, perhaps
  // finer, whose side i refines side i of this face).
  std::pair<double, double> l2_error(const ContactFace& mesh,
                                     const std::function<double(int side, const Eigen::VectorXd& xi, const Eigen::VectorXd& X)>& p,
                                     int points) const;

 private:
  const ContactFace& cf_;
  Eigen::VectorXd lambda_, weights_;
  std::vector<char> active_;
  Eigen::VectorXd X0_, n_;
};

// The point of the contact face with the smallest initial gap, and the
// obstacle normal there (sampled at the face's Gauss points and anchors).
std::pair<Eigen::VectorXd, Eigen::VectorXd> initial_contact_point(const ContactFace& cf, const Obstacle& obstacle);

// True when the face starts touching the obstacle over an extent rather
// than at a point -- a flat face on a plane: at two of its Gauss points more
// than 1e-4 of its size apart the initial gap is the smallest (to 1e-12 of
// the size) and the face is tangent to the obstacle (outward normals
// opposite to 1e-10).  Such a contact zone has no half width (no point it
// grows from).
bool touches_over_an_extent(const ContactFace& cf, const Obstacle& obstacle);

// Why the face can never press on the obstacle, judged from the reference
// geometry: it lies inside it everywhere (an obstacle normal that points away
// from the body), it faces away from it, or it is perpendicular to it
// everywhere.  nullopt when contact can happen.
std::optional<std::string> contact_cannot_happen(const ContactFace& cf, const Obstacle& obstacle);
// The deepest point of the face inside the obstacle at the reference
// geometry (the face's quadrature and corner points): depth = -gap > 0; a
// depth of 0 and an empty point when the face nowhere enters it.
struct Penetration {
  double depth = 0;
  Eigen::VectorXd point;
};
Penetration deepest_penetration(const ContactFace& cf, const Obstacle& obstacle);

}  // namespace igac
