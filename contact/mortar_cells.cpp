// SPDX-License-Identifier: BSD-3-Clause
#include "contact/mortar_cells.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

#include "engine/free_cores.hpp"
#include "engine/numerical_failure.hpp"
#include "engine/quadrature.hpp"

namespace igac {

namespace {

// A triangle of the slave element on which the projection's master
// parameters differ from their affine interpolation by more than this
// fraction of the master element's size (at an edge's midpoint) is halved
// (into 4), at most kMaxDepth times: curved faces.  On flat affine faces
// the projection is affine and the element's two triangles stay whole.
constexpr double kAffineTolerance = 1e-3;
constexpr int kMaxDepth = 3;
// A cell smaller than this fraction of the element is round-off (a master
// edge through a slave vertex): dropped.
constexpr double kSliver = 1e-14;
// Grid of slave points (per direction) whose projections tell an element
// inside one master element (integrated whole) from one to cut.
constexpr int kSamples = 5;
// An element of the current configuration whose samples all lie farther
// from the master than this many of its diameters is integrated whole.
constexpr double kFarInDiameters = 1.0;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a[0] * b[1] - a[1] * b[0]; }

// A point of the slave element: its Bezier coordinates s and the master
// side and parameters eta of its projection.
struct Vertex {
  Eigen::Vector2d s, eta;
  int side = 0;
  double distance = 0;  // from the slave point to its projection
};
using Polygon = std::vector<Vertex>;

Vertex midpoint(const Vertex& a, const Vertex& b, double t = 0.5) {
  return Vertex{a.s + t * (b.s - a.s), a.eta + t * (b.eta - a.eta), a.side};
}

// Splits a convex polygon (eta affine on it) along eta_d = beta.
void split(const Polygon& in, int d, double beta, Polygon& below, Polygon& above) {
  below.clear();
  above.clear();
  const size_t n = in.size();
  for (size_t i = 0; i < n; ++i) {
    const Vertex& p = in[i];
    const Vertex& q = in[(i + 1) % n];
    const double fp = p.eta[d] - beta, fq = q.eta[d] - beta;
    (fp <= 0 ? below : above).push_back(p);
    if ((fp < 0 && fq > 0) || (fp > 0 && fq < 0)) {
      Vertex x = midpoint(p, q, fp / (fp - fq));
      x.eta[d] = beta;
      below.push_back(x);
      above.push_back(x);
    } else if (fp == 0) {
      above.push_back(p);
    }
  }
}

double area(const Polygon& p) {
  double a = 0;
  for (size_t i = 0; i < p.size(); ++i) a += cross(p[i].s, p[(i + 1) % p.size()].s);
  return 0.5 * a;
}

struct Cutter {
  const BezierMesh& slave;
  int e;
  const MasterSurface& master;
  std::vector<MortarCell>& cells;
  bool cut = false;
  std::map<int, std::array<std::vector<double>, 2>> breaks;  // per master side and direction

  const std::vector<double>& breakpoints(int side, int d) {
    auto it = breaks.find(side);
    if (it == breaks.end()) {
      const NurbsPatch& p = master.side_patch(side);
      it = breaks.emplace(side, std::array<std::vector<double>, 2>{p.knots(0).breakpoints(), p.knots(1).breakpoints()})
               .first;
    }
    return it->second[d];
  }
  // Projections already made, by their (dyadic: exact) coordinates.
  std::map<std::pair<double, double>, Vertex> known;

  Vertex at(const Eigen::Vector2d& s) {
    const auto key = std::make_pair(s[0], s[1]);
    if (const auto it = known.find(key); it != known.end()) return it->second;
    const std::optional<MasterPoint> mp = master.project(slave.point(e, s));
    if (!mp && master.num_elements() == 0) throw std::invalid_argument("a contact's master surface has no elements");
    if (!mp) throw NumericalFailure("a slave point of a contact has a position that is not finite");
    return known.emplace(key, Vertex{s, Eigen::Vector2d(mp->xi[0], mp->xi[1]), mp->side, mp->distance}).first->second;
  }
  // The master element (knot span) holding eta along direction d.
  int span_index(int side, int d, double eta) {
    const std::vector<double>& b = breakpoints(side, d);
    return int(std::clamp(std::upper_bound(b.begin(), b.end(), eta), b.begin() + 1, b.end() - 1) - b.begin());
  }
  double span(int side, int d, double eta) {
    const std::vector<double>& b = breakpoints(side, d);
    const int i = span_index(side, d, eta);
    return b[i] - b[i - 1];
  }
  bool same_element(const Vertex& p, const Vertex& q) {
    return p.side == q.side && span_index(p.side, 0, p.eta[0]) == span_index(q.side, 0, q.eta[0]) &&
           span_index(p.side, 1, p.eta[1]) == span_index(q.side, 1, q.eta[1]);
  }
  bool affine_along(const Vertex& p, const Vertex& q, const Vertex& m) {
    if (m.side != p.side || q.side != p.side) return false;
    for (int d = 0; d < 2; ++d)
      if (std::abs(m.eta[d] - 0.5 * (p.eta[d] + q.eta[d])) > kAffineTolerance * span(p.side, d, m.eta[d])) return false;
    return true;
  }
  void add(const Polygon& p, int side, int depth) {
    if (!(area(p) > kSliver)) return;
    MortarCell c;
    c.side = side;
    c.depth = depth;
    for (const Vertex& v : p) c.polygon.push_back(v.s);
    cells.push_back(std::move(c));
  }
  void triangle(const Vertex& a, const Vertex& b, const Vertex& c, int depth) {
    const Vertex ab = at(0.5 * (a.s + b.s)), bc = at(0.5 * (b.s + c.s)), ca = at(0.5 * (c.s + a.s));
    // Inside one master element (corners and midpoints): whole, uncut.
    if (same_element(a, b) && same_element(a, c) && same_element(a, ab) && same_element(a, bc) && same_element(a, ca)) {
      add(Polygon{a, b, c}, a.side, depth);
      return;
    }
    if (!(affine_along(a, b, ab) && affine_along(b, c, bc) && affine_along(c, a, ca))) {
      if (depth < kMaxDepth) {
        triangle(a, ab, ca, depth + 1);
        triangle(ab, b, bc, depth + 1);
        triangle(ca, bc, c, depth + 1);
        triangle(bc, ca, ab, depth + 1);
        return;
      }
      if (a.side != b.side || b.side != c.side) {  // across master sides: whole
        cut = true;
        add(Polygon{a, b, c}, a.side, depth);
        return;
      }
    }
    // eta affine on the triangle: cut along every master breakpoint it spans.
    std::vector<Polygon> pieces{Polygon{a, b, c}}, next;
    Polygon below, above;
    for (int d = 0; d < 2; ++d) {
      const double lo = std::min({a.eta[d], b.eta[d], c.eta[d]}), hi = std::max({a.eta[d], b.eta[d], c.eta[d]});
      for (double beta : breakpoints(a.side, d)) {
        if (!(beta > lo && beta < hi)) continue;
        next.clear();
        for (const Polygon& p : pieces) {
          split(p, d, beta, below, above);
          for (Polygon* q : {&below, &above})
            if (q->size() >= 3) next.push_back(*q);
        }
        pieces.swap(next);
        cut = true;
      }
    }
    for (const Polygon& p : pieces) add(p, a.side, depth);
  }
};

}  // namespace

double polygon_area(const ParamPolygon& poly) {
  double a = 0;
  for (size_t i = 0; i < poly.size(); ++i) a += cross(poly[i], poly[(i + 1) % poly.size()]);
  return 0.5 * a;
}

bool mortar_cells(const BezierMesh& slave, int e, const MasterSurface& master, std::vector<MortarCell>& cells,
                  double far) {
  cells.clear();
  Cutter cutter{slave, e, master, cells, false, {}, {}};
  // Inside one master element: the element's own rule.
  bool one = true;
  for (int j = 0; j < kSamples; ++j)
    for (int i = 0; i < kSamples; ++i)
      one = cutter.same_element(cutter.at({double(i) / (kSamples - 1), double(j) / (kSamples - 1)}), cutter.at({0, 0})) && one;
  if (one) return false;
  // Far from the master (every sample): the element's own rule.
  if (std::isfinite(far)) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& [s, v] : cutter.known) nearest = std::min(nearest, v.distance);
    const Eigen::Vector2d s00(0, 0), s11(1, 1), s10(1, 0), s01(0, 1);
    const double diameter = std::max((slave.point(e, s00) - slave.point(e, s11)).norm(),
                                     (slave.point(e, s10) - slave.point(e, s01)).norm());
    if (nearest > far * diameter) return false;
  }
  const Vertex v00 = cutter.at({0, 0}), v10 = cutter.at({1, 0}), v11 = cutter.at({1, 1}), v01 = cutter.at({0, 1});
  cutter.triangle(v00, v10, v11, 0);
  cutter.triangle(v00, v11, v01, 0);
  if (!cutter.cut) cells.clear();
  return cutter.cut;
}

namespace {

// The quadrature points (Bezier parameters of the face patch) and weights
// of slave element e: its cells cut by the master's element edges, or its
// tensor rule when one master element holds it.
void cut_element_rule(const BezierMesh& mesh, int e, const MasterSurface& master, double far,
                      const TensorGaussRule& tensor, int ps, std::map<int, TensorGaussRule>& triangle_rules,
                      std::vector<MortarCell>& cells, std::vector<Eigen::Vector2d>& xi, std::vector<double>& weights) {
  const BezierElement& el = mesh.element(e);
  const Eigen::Vector2d lower(el.lower[0], el.lower[1]), span(el.upper[0] - el.lower[0], el.upper[1] - el.lower[1]);
  const double area = span[0] * span[1];
  auto add = [&](const Eigen::Vector2d& s, double w) {
    xi.push_back(lower + s.cwiseProduct(span));
    weights.push_back(w * area);
  };
  if (!mortar_cells(mesh, e, master, cells, far)) {  // inside one master element, or far: element-based
    for (size_t q = 0; q < tensor.points.size(); ++q) add(tensor.points[q], tensor.weights[q]);
    return;
  }
  // The degree of the mortar integrands on flat faces: B_K N_A, both slave
  // (4 p_s - 4) and master (2 p_s + 2 p_m - 4, total degree in s).
  int pm = 0;
  for (const MortarCell& c : cells) {
    const NurbsPatch& mp = master.side_patch(c.side);
    pm = std::max({pm, mp.degree(0), mp.degree(1)});
  }
  const int degree = std::max(4 * ps - 4, 2 * ps + 2 * pm - 4);
  const int n = std::max(2, degree / 2 + 1);
  for (const MortarCell& c : cells) {
    const int nc = c.depth > 0 ? 2 : n;
    const TensorGaussRule& rule = triangle_rules.try_emplace(nc, triangle_gauss_rule(nc)).first->second;
    // A fan from the first vertex (the cells are convex).
    const ParamPolygon& p = c.polygon;
    const Eigen::Vector2d& apex = p[0];
    for (size_t i = 1; i + 1 < p.size(); ++i) {
      const Eigen::Vector2d B = p[i] - apex, C = p[i + 1] - apex;
      const double tri = 0.5 * cross(B, C);
      if (tri == 0.0) continue;
      for (size_t q = 0; q < rule.points.size(); ++q)
        add(apex + rule.points[q][0] * B + rule.points[q][1] * C, rule.weights[q] * tri);
    }
  }
}

}  // namespace

void segmented_side_rule(const ContactSide& side, const Eigen::MatrixXd* u_side, const MasterSurface& master,
                         int points, std::vector<Eigen::VectorXd>& xi, std::vector<double>& weights) {
  xi.clear();
  weights.clear();
  const NurbsPatch& reference = side.face_patch;
  const BezierMesh mesh(u_side ? NurbsPatch(reference.all_knots(), reference.points() + *u_side, reference.weights())
                               : reference);
  const TensorGaussRule tensor = tensor_gauss_rule(2, points);
  const int ps = std::max(reference.degree(0), reference.degree(1));
  // Elements farther from the master than kFarInDiameters diameters are not
  // cut at a current position (the header says why); all are in the reference.
  const double far = u_side ? kFarInDiameters : std::numeric_limits<double>::infinity();
  // Each slave element cut on its own (the master's closest-point searches,
  // most of the cost): on the free cores, its points kept apart and joined
  // in element order, the same rule on any number of threads.
  const int ne = mesh.num_elements();
  std::vector<std::vector<Eigen::Vector2d>> element_xi(static_cast<size_t>(ne));
  std::vector<std::vector<double>> element_weights(static_cast<size_t>(ne));
  std::exception_ptr failure;
#pragma omp parallel num_threads(free_cores()) if (ne >= 8)
  {
    std::map<int, TensorGaussRule> triangle_rules;
    std::vector<MortarCell> cells;
#pragma omp for schedule(dynamic, 1)
    for (int e = 0; e < ne; ++e) {
      try {
        cut_element_rule(mesh, e, master, far, tensor, ps, triangle_rules, cells, element_xi[size_t(e)],
                         element_weights[size_t(e)]);
      } catch (...) {
#pragma omp critical(igac_segmented_side_rule)
        if (!failure) failure = std::current_exception();
      }
    }
  }
  if (failure) std::rethrow_exception(failure);
  for (int e = 0; e < ne; ++e) {
    for (const Eigen::Vector2d& x : element_xi[size_t(e)]) xi.push_back(x);
    weights.insert(weights.end(), element_weights[size_t(e)].begin(), element_weights[size_t(e)].end());
  }
}

}  // namespace igac
