// SPDX-License-Identifier: BSD-3-Clause
#include "contact/master_surface.hpp"

#include "engine/spline/bezier_extraction.hpp"
#include "engine/stopwatch.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace igac {

namespace {

constexpr int kLeafSize = 4;
constexpr int kNewtonIterations = 60;
constexpr int kGaussNewtonIterations = 6;

// Adds the seconds of its lifetime to the search's counters.
template <class Counters>
class Clock {
 public:
  explicit Clock(Counters& c) : c_(c) {}
  ~Clock() { c_.seconds += watch_.seconds(); }
  Clock(const Clock&) = delete;
  Clock& operator=(const Clock&) = delete;

 private:
  Counters& c_;
  Stopwatch watch_;
};

// Distance from x to the box [lo, hi] (0 inside).
double box_distance(const Eigen::VectorXd& x, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  return (x - x.cwiseMax(lo).cwiseMin(hi)).norm();
}

// The rational Bezier element's point S and tangents dS/ds at Bezier
// coordinates s, from its homogeneous control points (w x, w y, w z, w),
// first direction fastest.
template <int N, int SD>
void evaluate_bezier(const std::array<int, 2>& degree, const std::vector<std::array<double, 4>>& homogeneous,
                     const Eigen::Matrix<double, N, 1>& s, Eigen::Matrix<double, SD, 1>& S,
                     Eigen::Matrix<double, SD, N>& dS) {
  std::array<std::array<double, 32>, 2> B, dB;  // (not zeroed: only the first degree + 1 are read)
  for (int d = 0; d < N; ++d) bernstein(degree[d], s[d], B[d].data(), dB[d].data());
  if constexpr (N == 1) B[1][0] = 1, dB[1][0] = 0;
  const int n0 = degree[0] + 1, n1 = N > 1 ? degree[1] + 1 : 1;
  // Homogeneous sums sum B (w x, w) and their derivatives along s_0, s_1.
  std::array<double, 4> h{}, h0{}, h1{};
  for (int j = 0; j < n1; ++j)
    for (int i = 0; i < n0; ++i) {
      const std::array<double, 4>& p = homogeneous[size_t(i + n0 * j)];
      const double b = B[0][i] * B[1][j], b0 = dB[0][i] * B[1][j], b1 = B[0][i] * dB[1][j];
      for (int c = 0; c < 4; ++c) {
        h[c] += b * p[c];
        h0[c] += b0 * p[c];
        h1[c] += b1 * p[c];
      }
    }
  for (int c = 0; c < SD; ++c) {
    S[c] = h[c] / h[3];
    dS(c, 0) = (h0[c] - S[c] * h0[3]) / h[3];
    if constexpr (N > 1) dS(c, 1) = (h1[c] - S[c] * h1[3]) / h[3];
  }
}

// The Newton step -H^-1 g (Eigen's LDLT), or the Gauss-Newton one -JJ^-1 g
// where H is not positive definite.
template <int M>
Eigen::Matrix<double, M, 1> newton_step(const Eigen::Matrix<double, M, M>& H, const Eigen::Matrix<double, M, M>& JJ,
                                        const Eigen::Matrix<double, M, 1>& g) {
  Eigen::LDLT<Eigen::Matrix<double, M, M>> ldlt(H);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || ldlt.vectorD().minCoeff() <= 0) ldlt.compute(JJ);
  return -ldlt.solve(g);
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
    const BezierMesh mesh(sides_[k].current);
    const int n = mesh.param_dim();
    for (int i = 0; i < mesh.num_elements(); ++i) {
      const BezierElement& be = mesh.element(i);
      Element e;
      e.side = k;
      e.index = i;
      e.lo.resize(n);
      e.hi.resize(n);
      for (int d = 0; d < n; ++d) e.lo[d] = be.lower[d], e.hi[d] = be.upper[d], e.degree[d] = mesh.degree(d);
      e.points = be.points;
      e.weights = be.weights;
      e.homogeneous.assign(size_t(be.points.rows()), {0, 0, 0, 0});
      for (int a = 0; a < be.points.rows(); ++a) {
        for (int c = 0; c < be.points.cols(); ++c) e.homogeneous[a][c] = be.weights[a] * be.points(a, c);
        e.homogeneous[a][3] = be.weights[a];
      }
      // The Bezier control points hold the element (positive weights).
      e.box_lo = be.points.colwise().minCoeff().transpose();
      e.box_hi = be.points.colwise().maxCoeff().transpose();
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

struct MasterSurface::OnElement {
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 2, 1> s;                   // Bezier coordinates in [0, 1]^N
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1> S;                   // the point
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 2> J;      // dS/ds
  double distance = 0;                                                   // from the query
};

template <int N, int SD>
MasterSurface::OnElement MasterSurface::nearest_on_element(const Element& e, const Eigen::VectorXd& x_query) const {
  using Params = Eigen::Matrix<double, N, 1>;
  using Point = Eigen::Matrix<double, SD, 1>;
  using Tangents = Eigen::Matrix<double, SD, N>;
  using Hessian = Eigen::Matrix<double, N, N>;
  const Point x = x_query;
  auto inside = [&](const Params& s) { return Params(s.cwiseMax(0.0).cwiseMin(1.0)); };
  Params s = Params::Constant(0.5);
  Point S, Sn, Sa, Sb;
  Tangents J, Jn, Ja, Jb;
  evaluate_bezier<N, SD>(e.degree, e.homogeneous, s, S, J);
  double f = 0.5 * (S - x).squaredNorm();
  constexpr double h = 1e-6;
  // Gauss-Newton first (cheap, and fast for the points near the master that
  // contact asks about); Newton with the curvature term once Gauss-Newton
  // stalls or goes uphill (far from a curved master it diverges): the
  // Hessian by central differences of the exact gradient J^T (S - x).  J^T J
  // where that Hessian is not positive; a halving line search; kept inside
  // the element, in its Bezier coordinates s in [0, 1]^N.
  bool curvature = false;
  for (int it = 0; it < kNewtonIterations; ++it) {
    const Params g = J.transpose() * (S - x);
    if (g.norm() <= 1e-15 * (S - x).norm() * J.norm() + 1e-300) break;
    if (it >= kGaussNewtonIterations) curvature = true;
    const Hessian JJ = J.transpose() * J;
    Hessian H = JJ;
    if (curvature) {
      for (int j = 0; j < N; ++j) {
        Params a = s, b = s;
        a[j] += h;
        b[j] -= h;
        evaluate_bezier<N, SD>(e.degree, e.homogeneous, a, Sa, Ja);
        evaluate_bezier<N, SD>(e.degree, e.homogeneous, b, Sb, Jb);
        H.col(j) = (Ja.transpose() * (Sa - x) - Jb.transpose() * (Sb - x)) / (2 * h);
      }
      H = (H + H.transpose()).eval() / 2;
    }
    // Coordinates held at a bound of the element that the gradient pushes
    // outward stay there; Newton runs on the others.
    std::array<int, 2> free{};
    int m = 0;
    for (int j = 0; j < N; ++j)
      if (!((s[j] <= 0 && g[j] > 0) || (s[j] >= 1 && g[j] < 0))) free[m++] = j;
    if (m == 0) break;  // a corner of the element is the nearest point
    Params step = Params::Zero();
    if (m == N) {
      step = newton_step<N>(H, JJ, g);
    } else {  // (N = 2, one coordinate free)
      const int j = free[0];
      step[j] = newton_step<1>(Eigen::Matrix<double, 1, 1>(H(j, j)), Eigen::Matrix<double, 1, 1>(JJ(j, j)),
                               Eigen::Matrix<double, 1, 1>(g[j]))[0];
    }
    if (!step.allFinite()) break;
    // Converged: a step below round-off of the coordinates (the gradient
    // itself stalls at round-off of the coordinates, far above 0 when the
    // point is away from the surface).
    if (step.norm() <= 1e-13) break;
    double t = 1;
    Params next = inside(s + step);
    evaluate_bezier<N, SD>(e.degree, e.homogeneous, next, Sn, Jn);
    while (0.5 * (Sn - x).squaredNorm() > f * (1 + 1e-13) && t > 1e-6) {  // (round-off of f tolerated)
      curvature = true;
      t /= 2;
      next = inside(s + t * step);
      evaluate_bezier<N, SD>(e.degree, e.homogeneous, next, Sn, Jn);
    }
    const double moved = (next - s).norm();
    s = next;
    std::swap(S, Sn);
    std::swap(J, Jn);
    f = 0.5 * (S - x).squaredNorm();
    if (moved <= 1e-13) break;
  }
  OnElement out;
  out.s = s;
  out.S = S;
  out.J = J;
  out.distance = (x - S).norm();
  return out;
}

MasterSurface::OnElement MasterSurface::nearest_on_element(const Element& e, const Eigen::VectorXd& x) const {
  const int n = int(e.lo.size()), sd = int(x.size());
  if (n == 1 && sd == 2) return nearest_on_element<1, 2>(e, x);
  if (n == 2 && sd == 3) return nearest_on_element<2, 3>(e, x);
  throw std::invalid_argument(
      fmt::format("a master surface of parametric dimension {} in {}D space cannot be searched", n, sd));
}

MasterPoint MasterSurface::master_point(const Element& e, const OnElement& nearest, const Eigen::VectorXd& x) const {
  MasterPoint mp;
  mp.side = e.side;
  mp.element = e.index;
  mp.xi = e.lo + nearest.s.cwiseProduct(e.hi - e.lo);
  mp.x = nearest.S;
  // (dS/ds is dS/dxi with each column scaled by a positive span length: the
  // same outward direction.)
  mp.normal = face_area_vector(sides_[e.side].side.face, nearest.J).normalized();
  mp.distance = nearest.distance;
  mp.gap = (x - mp.x).dot(mp.normal);
  return mp;
}

std::optional<MasterPoint> MasterSurface::project(const Eigen::VectorXd& x, int* candidates) const {
  const Clock clock(counters_);
  ++counters_.queries;
  if (nodes_.empty()) return std::nullopt;
  const Element* best_element = nullptr;
  OnElement best;
  double bound = std::numeric_limits<double>::infinity();
  // A point on the surface to round-off: no other element can be nearer.
  const double on_surface = 1e-14 * (nodes_[0].hi - nodes_[0].lo).norm();
  // Depth-first, nearer child first: at most one pending sibling per level
  // of the median-split tree (depth log2(elements)).
  std::array<int, 128> stack{};
  int pending = 0;
  stack[pending++] = 0;
  while (pending > 0) {
    const Node& node = nodes_[stack[--pending]];
    if (box_distance(x, node.lo, node.hi) >= bound) continue;
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const Element& e = elements_[order_[i]];
        if (box_distance(x, e.box_lo, e.box_hi) >= bound) continue;
        ++counters_.candidates;
        if (candidates) ++*candidates;
        OnElement nearest = nearest_on_element(e, x);
        if (nearest.distance < bound) {
          bound = nearest.distance;
          best = std::move(nearest);
          best_element = &e;
          if (bound <= on_surface) return master_point(e, best, x);
        }
      }
      continue;
    }
    // Nearer child on top of the stack: visited first.
    const double dl = box_distance(x, nodes_[node.left].lo, nodes_[node.left].hi);
    const double dr = box_distance(x, nodes_[node.right].lo, nodes_[node.right].hi);
    const bool left_first = dl <= dr;
    stack[pending++] = left_first ? node.right : node.left;
    stack[pending++] = left_first ? node.left : node.right;
  }
  if (!best_element) return std::nullopt;  // (no finite distance: x not finite)
  return master_point(*best_element, best, x);
}

std::optional<MasterPoint> MasterSurface::project_by_every_element(const Eigen::VectorXd& x) const {
  const Element* best_element = nullptr;
  OnElement best;
  for (const Element& e : elements_) {
    OnElement nearest = nearest_on_element(e, x);
    if (!best_element || nearest.distance < best.distance) best = std::move(nearest), best_element = &e;
  }
  if (!best_element) return std::nullopt;
  return master_point(*best_element, best, x);
}

}  // namespace igac
