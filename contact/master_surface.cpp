// SPDX-License-Identifier: BSD-3-Clause
#include "contact/master_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace igac {

namespace {

constexpr int kLeafSize = 4;
constexpr int kNewtonIterations = 60;
constexpr int kGaussNewtonIterations = 6;

// Distance from x to the box [lo, hi] (0 inside).
double box_distance(const Eigen::VectorXd& x, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  return (x - x.cwiseMax(lo).cwiseMin(hi)).norm();
}

}  // namespace

MasterSurface::MasterSurface(const Body& body, const std::vector<PatchSide>& sides) {
  for (const PatchSide& s : sides) {
    NurbsPatch p = body.side_patch(s);
    sides_.push_back(Side{s, p, p, body.side_control_points(s)});
  }
  build_elements();
}

void MasterSurface::update(const Eigen::MatrixXd& u) {
  for (Side& s : sides_) {
    Eigen::MatrixXd P = s.reference.points();
    for (int i = 0; i < P.rows(); ++i) P.row(i) += u.row(s.cps[i]);
    s.current = NurbsPatch(s.reference.all_knots(), std::move(P), s.reference.weights());
  }
  build_elements();
}

void MasterSurface::build_elements() {
  elements_.clear();
  for (int k = 0; k < int(sides_.size()); ++k) {
    const NurbsPatch& p = sides_[k].current;
    const int n = p.param_dim();
    std::array<std::vector<double>, 2> breaks;
    std::array<std::vector<int>, 2> spans;
    std::array<int, 2> ne{1, 1};
    for (int d = 0; d < n; ++d) {
      breaks[d] = p.knots(d).breakpoints();
      spans[d] = p.knots(d).element_spans();
      ne[d] = int(spans[d].size());
    }
    for (int j = 0; j < ne[1]; ++j)
      for (int i = 0; i < ne[0]; ++i) {
        Element e;
        e.side = k;
        e.index = i + ne[0] * j;
        e.lo.resize(n);
        e.hi.resize(n);
        const std::array<int, 2> ij{i, j};
        for (int d = 0; d < n; ++d) e.lo[d] = breaks[d][ij[d]], e.hi[d] = breaks[d][ij[d] + 1];
        // The control points that support the element: a box that holds it.
        e.box_lo = Eigen::VectorXd::Constant(p.space_dim(), std::numeric_limits<double>::infinity());
        e.box_hi = -e.box_lo;
        const int p0 = p.degree(0), p1 = n > 1 ? p.degree(1) : 0;
        for (int b = 0; b <= p1; ++b)
          for (int a = 0; a <= p0; ++a) {
            std::array<int, 3> mi{spans[0][i] - p0 + a, n > 1 ? spans[1][j] - p1 + b : 0, 0};
            const Eigen::VectorXd X = p.points().row(p.index(mi)).transpose();
            e.box_lo = e.box_lo.cwiseMin(X);
            e.box_hi = e.box_hi.cwiseMax(X);
          }
        elements_.push_back(std::move(e));
      }
  }
  order_.resize(elements_.size());
  std::iota(order_.begin(), order_.end(), 0);
  nodes_.clear();
  if (!elements_.empty()) build_tree(0, int(elements_.size()));
}

int MasterSurface::build_tree(int first, int count) {
  const int id = int(nodes_.size());
  nodes_.emplace_back();
  Eigen::VectorXd lo = elements_[order_[first]].box_lo, hi = elements_[order_[first]].box_hi;
  for (int i = first; i < first + count; ++i) {
    lo = lo.cwiseMin(elements_[order_[i]].box_lo);
    hi = hi.cwiseMax(elements_[order_[i]].box_hi);
  }
  nodes_[id].lo = lo;
  nodes_[id].hi = hi;
  if (count <= kLeafSize) {
    nodes_[id].first = first;
    nodes_[id].count = count;
    return id;
  }
  // Split at the median of the box centres along the box's longest axis.
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](int a, int b) {
                     return elements_[a].box_lo[axis] + elements_[a].box_hi[axis] <
                            elements_[b].box_lo[axis] + elements_[b].box_hi[axis];
                   });
  const int left = build_tree(first, half);
  const int right = build_tree(first + half, count - half);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

MasterPoint MasterSurface::project_on_element(const Element& e, const Eigen::VectorXd& x) const {
  const Side& side = sides_[e.side];
  const NurbsPatch& p = side.current;
  const int n = int(e.lo.size());
  auto inside = [&](const Eigen::VectorXd& xi) { return Eigen::VectorXd(xi.cwiseMax(e.lo).cwiseMin(e.hi)); };
  // The point and its tangents in one evaluation.
  auto evaluate = [&](const Eigen::VectorXd& xi, Eigen::VectorXd& S, Eigen::MatrixXd& J) {
    S = p.field(p.points(), xi, &J);
  };
  Eigen::VectorXd xi = (e.lo + e.hi) / 2, S, Sn, Sa, Sb;
  Eigen::MatrixXd J, Jn, Ja, Jb;
  evaluate(xi, S, J);
  double f = 0.5 * (S - x).squaredNorm();
  const Eigen::VectorXd h = 1e-6 * (e.hi - e.lo);
  // Gauss-Newton first (cheap, and fast for the points near the master that
  // contact asks about); Newton with the curvature term once Gauss-Newton
  // stalls or goes uphill (far from a curved master it diverges): the
  // Hessian by central differences of the exact gradient J^T (S - x).  J^T J
  // where that Hessian is not positive; a halving line search; kept inside
  // the element.
  bool curvature = false;
  for (int it = 0; it < kNewtonIterations; ++it) {
    const Eigen::VectorXd g = J.transpose() * (S - x);
    if (g.norm() <= 1e-15 * (S - x).norm() * J.norm() + 1e-300) break;
    if (it >= kGaussNewtonIterations) curvature = true;
    Eigen::MatrixXd H = J.transpose() * J;
    if (curvature) {
      for (int j = 0; j < n; ++j) {
        Eigen::VectorXd a = xi, b = xi;
        a[j] += h[j];
        b[j] -= h[j];
        evaluate(a, Sa, Ja);
        evaluate(b, Sb, Jb);
        H.col(j) = (Ja.transpose() * (Sa - x) - Jb.transpose() * (Sb - x)) / (2 * h[j]);
      }
      H = (H + H.transpose()).eval() / 2;
    }
    // Parameters held at a bound of the element that the gradient pushes
    // outward stay there; Newton runs on the others.
    std::vector<int> free;
    for (int j = 0; j < n; ++j)
      if (!((xi[j] <= e.lo[j] && g[j] > 0) || (xi[j] >= e.hi[j] && g[j] < 0))) free.push_back(j);
    if (free.empty()) break;  // a corner of the element is the nearest point
    const int m = int(free.size());
    Eigen::MatrixXd Hf(m, m), JtJ(m, m);
    Eigen::VectorXd gf(m);
    const Eigen::MatrixXd JJ = J.transpose() * J;
    for (int a = 0; a < m; ++a) {
      gf[a] = g[free[a]];
      for (int b = 0; b < m; ++b) Hf(a, b) = H(free[a], free[b]), JtJ(a, b) = JJ(free[a], free[b]);
    }
    Eigen::LDLT<Eigen::MatrixXd> ldlt(Hf);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || ldlt.vectorD().minCoeff() <= 0) ldlt.compute(JtJ);
    const Eigen::VectorXd sf = -ldlt.solve(gf);
    if (!sf.allFinite()) break;
    Eigen::VectorXd step = Eigen::VectorXd::Zero(n);
    for (int a = 0; a < m; ++a) step[free[a]] = sf[a];
    // Converged: a step below round-off of the parameters (the gradient
    // itself stalls at round-off of the coordinates, far above 0 when the
    // point is away from the surface).
    if (step.norm() <= 1e-13 * (e.hi - e.lo).norm()) break;
    double t = 1;
    Eigen::VectorXd next = inside(xi + step);
    evaluate(next, Sn, Jn);
    while (0.5 * (Sn - x).squaredNorm() > f * (1 + 1e-13) && t > 1e-6) {  // (round-off of f tolerated)
      curvature = true;
      t /= 2;
      next = inside(xi + t * step);
      evaluate(next, Sn, Jn);
    }
    const double moved = (next - xi).norm();
    xi = next;
    std::swap(S, Sn);
    std::swap(J, Jn);
    f = 0.5 * (S - x).squaredNorm();
    if (moved <= 1e-13 * (e.hi - e.lo).norm()) break;
  }
  MasterPoint mp;
  mp.side = e.side;
  mp.element = e.index;
  mp.xi = xi;
  mp.x = S;
  mp.normal = face_area_vector(side.side.face, J).normalized();
  mp.distance = (x - S).norm();
  mp.gap = (x - S).dot(mp.normal);
  return mp;
}

std::optional<MasterPoint> MasterSurface::project(const Eigen::VectorXd& x) const {
  last_candidates_ = 0;
  if (nodes_.empty()) return std::nullopt;
  std::optional<MasterPoint> best;
  double bound = std::numeric_limits<double>::infinity();
  // A point on the surface to round-off: no other element can be nearer.
  const double on_surface = 1e-14 * (nodes_[0].hi - nodes_[0].lo).norm();
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const Node& node = nodes_[stack.back()];
    stack.pop_back();
    if (box_distance(x, node.lo, node.hi) >= bound) continue;
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const Element& e = elements_[order_[i]];
        if (box_distance(x, e.box_lo, e.box_hi) >= bound) continue;
        ++last_candidates_;
        MasterPoint mp = project_on_element(e, x);
        if (mp.distance < bound) {
          bound = mp.distance;
          best = std::move(mp);
          if (bound <= on_surface) return best;
        }
      }
      continue;
    }
    // Nearer child on top of the stack: visited first.
    const double dl = box_distance(x, nodes_[node.left].lo, nodes_[node.left].hi);
    const double dr = box_distance(x, nodes_[node.right].lo, nodes_[node.right].hi);
    if (dl <= dr) stack.insert(stack.end(), {node.right, node.left});
    else stack.insert(stack.end(), {node.left, node.right});
  }
  return best;
}

std::optional<MasterPoint> MasterSurface::project_by_every_element(const Eigen::VectorXd& x) const {
  std::optional<MasterPoint> best;
  for (const Element& e : elements_) {
    MasterPoint mp = project_on_element(e, x);
    if (!best || mp.distance < best->distance) best = std::move(mp);
  }
  return best;
}

}  // namespace igac
