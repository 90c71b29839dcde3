// SPDX-License-Identifier: BSD-3-Clause
#include "contact/pressure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace igac {

double HertzSolution::pressure(double r) const { return r < a ? p0 * std::sqrt(1 - r * r / (a * a)) : 0.0; }

HertzSolution hertz_cylinder(double R, double P, double E, double nu) {
  HertzSolution h;
  h.a = std::sqrt(8 * R * R * P * (1 - nu * nu) / (std::numbers::pi * E));
  h.p0 = h.a > 0 ? 4 * R * P / (std::numbers::pi * h.a) : 0.0;  // no load: no contact zone, no pressure
  return h;
}

HertzSolution hertz_sphere(double R, double P, double E, double nu) {
  HertzSolution h;
  h.a = std::cbrt(3 * std::numbers::pi * R * R * R * P * (1 - nu * nu) / (4 * E));
  h.p0 = h.a > 0 ? 3 * R * R * P / (2 * h.a * h.a) : 0.0;
  return h;
}

ContactPressure::ContactPressure(const ContactFace& cf, Eigen::VectorXd lambda, Eigen::VectorXd weights,
                                 std::vector<char> active, Eigen::VectorXd X0, Eigen::VectorXd normal)
    : cf_(cf), lambda_(std::move(lambda)), weights_(std::move(weights)), active_(std::move(active)),
      X0_(std::move(X0)), n_(std::move(normal)) {}

double ContactPressure::r_of(const Eigen::VectorXd& X) const {
  const Eigen::VectorXd d = X - X0_;
  return (d - d.dot(n_) * n_).norm();
}

double ContactPressure::pressure_at(int side, const Eigen::VectorXd& xi) const {
  std::vector<int> idx;
  std::vector<double> val;
  const ContactSide& s = cf_.sides[side];
  s.space.basis(xi, idx, val);
  double p = 0;
  for (size_t k = 0; k < idx.size(); ++k) p -= lambda_[s.first_multiplier + idx[k]] * val[k];
  return p;
}

namespace {

// A multiplier is pressed above round-off of the largest pressure (an S0
// mean of 1e-12 p0 is a multiplier that is active with nothing to carry).
constexpr double kPressedFraction = 1e-6;

}  // namespace

ContactPressure::Edge ContactPressure::edge_along(int side, const std::function<Eigen::VectorXd(double)>& line,
                                                  const std::vector<double>& b, double max_pressure) const {
  const ContactSide& cs = cf_.sides[side];
  const NurbsPatch& fp = cs.face_patch;
  const int ne = int(b.size()) - 1;
  if (ne < 1 || !(max_pressure > 0)) return {};
  std::vector<double> rb(b.size());
  for (size_t j = 0; j < b.size(); ++j) rb[j] = r_of(fp.point(line(b[j])));
  const double pressed = kPressedFraction * max_pressure;
  if (cs.space.degree() > 0) {
    // Continuous multipliers: their nodal values at the breakpoints.  The
    // pressure of a smooth contact is elliptic, p = c sqrt(a^2 - r^2): p^2
    // is linear in r^2 through the last two pressed nodes, and vanishes at
    // the edge, which lies before the next (unpressed) node.
    std::vector<double> p(b.size());
    for (size_t j = 0; j < b.size(); ++j) p[j] = pressure_at(side, line(b[j]));
    int last = -1;
    for (int j = 0; j <= ne; ++j)
      if (p[j] > pressed) last = j;
    if (last < 0) return {};
    if (last == ne) return {rb[ne], true};
    double a = rb[last] + (rb[last + 1] - rb[last]) * p[last] / (p[last] - std::min(p[last + 1], 0.0));
    if (last >= 1 && p[last - 1] > p[last]) {
      const double r1 = rb[last - 1], r2 = rb[last], q1 = p[last - 1] * p[last - 1], q2 = p[last] * p[last];
      a = std::sqrt(r2 * r2 + q2 * (r2 * r2 - r1 * r1) / (q1 - q2));
    }
    return {std::clamp(a, rb[last], rb[last + 1]), false};
  }
  // S0: one constant per element, the element's mean of p.  The edge lies
  // in the element after the last pressed one or in that one: the means of
  // the elliptic sqrt(a^2 - r^2) over the last two pressed elements
  // (integrated over the whole face element: in 3D r varies across the row
  // too) must stand in the ratio of their multipliers; solved for a by
  // bisection.
  std::vector<double> mean(static_cast<size_t>(ne));
  for (int e = 0; e < ne; ++e) mean[size_t(e)] = pressure_at(side, line(0.5 * (b[e] + b[e + 1])));
  int last = -1;
  for (int e = 0; e < ne; ++e)
    if (mean[size_t(e)] > pressed) last = e;
  if (last < 0) return {};
  // the middle of the element after the last pressed one (the side's end)
  const bool to_the_end = last + 1 == ne;
  const double next_middle = to_the_end ? rb[ne] : 0.5 * (rb[last + 1] + rb[last + 2]);
  if (last == 0) return {next_middle, to_the_end};  // one pressed element: nothing to fit
  std::vector<int> idx;
  std::vector<double> val;
  auto element_of = [&](int e) {
    cs.space.basis(line(0.5 * (b[e] + b[e + 1])), idx, val);
    return idx.front();  // S0: multiplier k of the side lives on its face element k
  };
  const PatchQuadrature fine = cs.quadrature(10);
  ElementData ed;
  std::array<std::vector<std::pair<double, double>>, 2> rw;  // (r, weight) at the points
  const std::array<int, 2> elems{element_of(last - 1), element_of(last)};
  for (int k = 0; k < 2; ++k) {
    fine.evaluate(elems[k], ed, false);
    for (int q = 0; q < ed.JxW.size(); ++q) rw[k].push_back({r_of(ed.X.row(q).transpose()), ed.JxW[q]});
  }
  auto sqrt_mean = [&](int k, double a) {
    double m = 0, w = 0;
    for (const auto& [r, wq] : rw[k]) {
      m += std::sqrt(std::max(a * a - r * r, 0.0)) * wq;
      w += wq;
    }
    return m / w;
  };
  const double ratio = -lambda_[cs.first_multiplier + elems[1]] / -lambda_[cs.first_multiplier + elems[0]];
  auto f = [&](double a) { return sqrt_mean(1, a) / sqrt_mean(0, a) - ratio; };
  const double r1 = rb[last], r2 = rb[last + 1];
  double lo = r1, hi = r2;
  for (const auto& [r, w] : rw[1]) lo = std::min(lo, r);
  lo += 1e-12 * (r2 - r1);
  if (f(lo) >= 0) return {r1, false};                  // the last element barely carries: the edge is at its start
  if (f(hi) <= 0) return {next_middle, to_the_end};  // pressed throughout: the edge lies in the next element
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0 ? lo : hi) = mid;
  }
  return {0.5 * (lo + hi), false};
}

PressureReport ContactPressure::report() const {
  PressureReport rep;
  for (const ContactSide& s : cf_.sides)
    for (int k = 0; k < s.space.size(); ++k) {
      const int K = s.first_multiplier + k;
      const Eigen::VectorXd X = s.face_patch.point(s.space.anchor(k));
      rep.multipliers.push_back({r_of(X), -lambda_[K]});
      rep.max_pressure = std::max(rep.max_pressure, -lambda_[K]);
      rep.total_force -= lambda_[K] * weights_[K];
      rep.active += active_[K] ? 1 : 0;
    }
  // Where X0 lies: the corner of a side nearest to it, or (X0 inside a
  // side, no symmetry plane through it) the face's quadrature point it is.
  int side = 0;
  std::array<bool, 2> at_end{false, false};  // which corner of the side holds X0
  double best = std::numeric_limits<double>::infinity(), size = 0;
  for (int si = 0; si < int(cf_.sides.size()); ++si) {
    const NurbsPatch& fp = cf_.sides[si].face_patch;
    size = std::max(size, (fp.points().colwise().maxCoeff() - fp.points().colwise().minCoeff()).norm());
    const int fd = fp.param_dim();
    for (int c = 0; c < (1 << fd); ++c) {
      Eigen::VectorXd xi(fd);
      for (int d = 0; d < fd; ++d) xi[d] = (c >> d) & 1 ? fp.knots(d).last() : fp.knots(d).first();
      const double dist = (fp.point(xi) - X0_).norm();
      if (dist < best) {
        best = dist;
        side = si;
        for (int d = 0; d < fd; ++d) at_end[d] = (c >> d) & 1;
      }
    }
  }
  if (best > 1e-8 * size) {
    // X0 inside a side: the edge along each parametric direction through
    // it, both ways; the half width is their mean (Hertz's a where the
    // zone is symmetric), over the lines whose edge lies on this side (a
    // line pressed to the side's end, X0 next to another side, says only
    // that its edge is further).  No profile.
    Eigen::VectorXd xi0;
    double nearest = std::numeric_limits<double>::infinity();
    cf_.face_quadrature(gauss_points_for(cf_.degree)).for_each_element([&](int s, const auto& v) {
      for (int q = 0; q < v.n_q; ++q) {
        const double dist = (Eigen::VectorXd(v.X[q]) - X0_).norm();
        if (dist < nearest) {
          nearest = dist;
          side = s;
          xi0 = Eigen::VectorXd(v.xi[q]);
        }
      }
    });
    const NurbsPatch& fp = cf_.sides[side].face_patch;
    double sum = 0, furthest = 0;
    int lines = 0;
    for (int d = 0; d < fp.param_dim(); ++d)
      for (const int sign : {1, -1}) {
        std::vector<double> b{xi0[d]};
        std::vector<double> breaks = fp.knots(d).breakpoints();
        if (sign < 0) std::reverse(breaks.begin(), breaks.end());
        for (double t : breaks)
          if (sign * (t - xi0[d]) > 0) b.push_back(t);
        const auto line = [&](double t) {
          Eigen::VectorXd xi = xi0;
          xi[d] = t;
          return xi;
        };
        const Edge edge = edge_along(side, line, b, rep.max_pressure);
        furthest = std::max(furthest, edge.r);
        if (edge.r > 0 && !edge.at_end_of_side) sum += edge.r, ++lines;
      }
    rep.half_width = lines ? sum / lines : furthest;
    return rep;
  }
  // X0 at a corner (a symmetry plane through it): the pressure profile along
  // the face edge that starts there (the whole side in 2D; in 3D the edge
  // on a symmetry plane): element values for S0, nodal values at the
  // breakpoints, and the P1 re-interpolation; the edge along it.
  const ContactSide& cs = cf_.sides[side];
  const NurbsPatch& fp = cs.face_patch;
  const int fd = fp.param_dim();
  auto line = [&](double t) {
    Eigen::VectorXd xi(fd);
    xi[0] = t;
    if (fd == 2) xi[1] = at_end[1] ? fp.knots(1).last() : fp.knots(1).first();
    return xi;
  };
  std::vector<double> b = fp.knots(0).breakpoints();
  if (at_end[0]) std::reverse(b.begin(), b.end());
  const int ne = int(b.size()) - 1;
  std::vector<double> rb(b.size());
  for (size_t j = 0; j < b.size(); ++j) rb[j] = r_of(fp.point(line(b[j])));
  const bool constants = cs.space.degree() == 0;
  std::vector<double> mean(ne);
  for (int e = 0; e < ne; ++e) mean[e] = pressure_at(side, line(0.5 * (b[e] + b[e + 1])));
  for (size_t j = 0; j < b.size(); ++j) {
    if (!constants) {
      rep.p1.push_back({rb[j], pressure_at(side, line(b[j]))});
      continue;
    }
    // nodal value = length-weighted mean of the adjacent element constants
    double sum = 0, w = 0;
    for (int e : {int(j) - 1, int(j)})
      if (e >= 0 && e < ne) {
        const double len = std::abs(rb[e + 1] - rb[e]);
        sum += mean[e] * len;
        w += len;
      }
    rep.p1.push_back({rb[j], w > 0 ? sum / w : 0.0});
  }
  rep.half_width = edge_along(side, line, b, rep.max_pressure).r;
  return rep;
}

std::pair<double, double> ContactPressure::l2_error(
    const ContactFace& mesh, const std::function<double(int, const Eigen::VectorXd&, const Eigen::VectorXd&)>& p,
    int points) const {
  if (mesh.sides.size() != cf_.sides.size())
    throw std::invalid_argument("pressure error: the two contact faces have different sides");
  double e2 = 0, n2 = 0;
  Eigen::VectorXd xi, X;
  mesh.face_quadrature(points).for_each_element([&](int s, const auto& v) {
    for (int q = 0; q < v.n_q; ++q) {
      xi = v.xi[q];
      X = v.X[q];
      const double ref = p(s, xi, X);
      const double ph = pressure_at(s, xi);
      e2 += (ph - ref) * (ph - ref) * v.JxW[q];
      n2 += ref * ref * v.JxW[q];
    }
  });
  return {std::sqrt(e2), std::sqrt(n2)};
}

namespace {

// Visits the face's corner control points (normal unknown: empty) and its
// Gauss points (with the face's outward unit normal).
template <class Visit>
void for_each_face_sample(const ContactFace& cf, Visit&& visit) {
  const Eigen::VectorXd no_normal;
  auto corners = [&](const ContactSide& s) {
    const NurbsPatch& fp = s.face_patch;
    for (int i = 0; i < fp.num_control_points(); ++i) {
      const auto mi = fp.multi_index(i);
      bool corner = true;
      for (int d = 0; d < fp.param_dim(); ++d) corner = corner && (mi[d] == 0 || mi[d] == fp.num_basis(d) - 1);
      if (corner) visit(fp.points().row(i).transpose().eval(), no_normal);
    }
  };
  int next = 0;  // side by side: its corners, then its points
  cf.face_quadrature(gauss_points_for(cf.degree)).for_each_element([&](int s, const auto& v) {
    while (next <= s) corners(cf.sides[next++]);
    for (int q = 0; q < v.n_q; ++q) visit(Eigen::VectorXd(v.X[q]), Eigen::VectorXd(v.normal[q]));
  });
  while (next < int(cf.sides.size())) corners(cf.sides[next++]);
}

}  // namespace

std::pair<Eigen::VectorXd, Eigen::VectorXd> initial_contact_point(const ContactFace& cf, const Obstacle& obstacle) {
  double best = std::numeric_limits<double>::infinity();
  Eigen::VectorXd X0, n0;
  for_each_face_sample(cf, [&](const Eigen::VectorXd& X, const Eigen::VectorXd&) {
    const ObstacleProbe pr = obstacle.probe(X);
    if (pr.gap < best) {
      best = pr.gap;
      X0 = X;
      n0 = pr.normal;
    }
  });
  return {X0, n0};
}

bool touches_over_an_extent(const ContactFace& cf, const Obstacle& obstacle) {
  struct Sample {
    Eigen::VectorXd X;
    double gap;
    bool tangent;  // the face's outward normal opposite the obstacle's: the gap is stationary there
  };
  std::vector<Sample> samples;
  Eigen::VectorXd lo, hi;
  for_each_face_sample(cf, [&](const Eigen::VectorXd& X, const Eigen::VectorXd& n_face) {
    const ObstacleProbe pr = obstacle.probe(X);
    samples.push_back({X, pr.gap, n_face.size() > 0 && n_face.dot(pr.normal) < -1 + 1e-10});
    lo = lo.size() ? lo.cwiseMin(X).eval() : X;
    hi = hi.size() ? hi.cwiseMax(X).eval() : X;
  });
  if (samples.empty()) return false;
  const double size = (hi - lo).norm();
  double best = std::numeric_limits<double>::infinity();
  for (const Sample& s : samples) best = std::min(best, s.gap);
  // Two points far apart where the face lies on the obstacle at the smallest
  // gap (points symmetric about a round contact's centre share the gap but
  // are not tangent to the obstacle).
  const Eigen::VectorXd* first = nullptr;
  for (const Sample& s : samples) {
    if (!s.tangent || s.gap > best + 1e-12 * size) continue;
    if (!first) first = &s.X;
    else if ((s.X - *first).norm() > 1e-4 * size) return true;
  }
  return false;
}

std::optional<std::string> contact_cannot_happen(const ContactFace& cf, const Obstacle& obstacle) {
  // Judged where the face is nearest the obstacle's surface (smallest |g_n|):
  // there a face that can press on the obstacle has its outward normal
  // against the obstacle's (n_face . n_obstacle < 0).  An initial
  // penetration is allowed: the solve pushes the body out.
  // A face that nowhere turns toward the obstacle (most_facing <= 0:
  // perpendicular to it, a side face along a plane) can slide on it, never press.
  double nearest = std::numeric_limits<double>::infinity(), facing = -1;
  double most_facing = -std::numeric_limits<double>::infinity();
  for_each_face_sample(cf, [&](const Eigen::VectorXd& X, const Eigen::VectorXd& n_face) {
    if (n_face.size() == 0) return;  // corners carry no normal
    const ObstacleProbe pr = obstacle.probe(X);
    most_facing = std::max(most_facing, -n_face.dot(pr.normal));
    if (std::abs(pr.gap) < nearest) {
      nearest = std::abs(pr.gap);
      facing = n_face.dot(pr.normal);
    }
  });
  if (facing > 1e-6)
    return fmt::format("the contact face faces away from the obstacle (its outward normal makes {:.0f} degrees with "
                       "the obstacle's outward normal where they are nearest, contact needs more than 90): is the "
                       "obstacle's normal reversed, or the face the wrong one?",
                       std::acos(std::clamp(facing, -1.0, 1.0)) * 180 / std::numbers::pi);
  if (most_facing <= 1e-6 && std::isfinite(most_facing))
    return fmt::format("the contact face is perpendicular to the obstacle (its outward normal makes {:.1f} degrees or "
                       "more with the obstacle's outward normal everywhere, contact needs more than 90): it can slide "
                       "along the obstacle but never press on it; is the face the wrong one?",
                       std::acos(std::clamp(-most_facing, -1.0, 1.0)) * 180 / std::numbers::pi);
  return std::nullopt;
}

Penetration deepest_penetration(const ContactFace& cf, const Obstacle& obstacle) {
  Penetration deepest;
  for_each_face_sample(cf, [&](const Eigen::VectorXd& X, const Eigen::VectorXd&) {
    if (const double depth = -obstacle.probe(X).gap; depth > deepest.depth) deepest = {depth, X};
  });
  return deepest;
}

}  // namespace igac
