// SPDX-License-Identifier: BSD-3-Clause
#include "contact/master_surface.hpp"

#include "engine/spline/bezier_extraction.hpp"
#include "engine/stopwatch.hpp"

#include <Eigen/Geometry>
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

// An orthonormal frame (columns) whose last column is along normal and
// first along tangent's part across it; the axes where they are too short
// or too parallel to fix one (a collapsed element, a node whose elements
// face many ways).
Eigen::MatrixXd fitted_frame(const Eigen::VectorXd& tangent, const Eigen::VectorXd& normal) {
  const int sd = int(normal.size());
  if (!(normal.norm() > 0)) return Eigen::MatrixXd::Identity(sd, sd);
  Eigen::MatrixXd frame(sd, sd);
  frame.col(sd - 1) = normal.normalized();
  if (sd == 2) {
    frame(0, 0) = frame(1, 1);
    frame(1, 0) = -frame(0, 1);
    return frame;
  }
  const Eigen::Vector3d t = tangent - tangent.dot(frame.col(2)) * frame.col(2);
  if (!(t.norm() > 1e-6 * tangent.norm())) return Eigen::MatrixXd::Identity(sd, sd);
  frame.col(0) = t.normalized();
  frame.col(1) = Eigen::Vector3d(frame.col(2)).cross(Eigen::Vector3d(frame.col(0)));
  return frame;
}

// The tangent and normal directions of a Bezier element from its control
// points (n_local x dim, first direction fastest): the sum of the two
// chords along the first direction, and the normal of the two chord sums
// (0 where the element has collapsed).
std::pair<Eigen::VectorXd, Eigen::VectorXd> element_directions(const Eigen::MatrixXd& points,
                                                               const std::array<int, 2>& degree, int param_dim) {
  const int sd = int(points.cols());
  const int n0 = degree[0] + 1, n1 = param_dim > 1 ? degree[1] + 1 : 1;
  auto P = [&](int i, int j) -> Eigen::VectorXd { return points.row(i + n0 * j).transpose(); };
  const Eigen::VectorXd a = (P(n0 - 1, 0) - P(0, 0)) + (P(n0 - 1, n1 - 1) - P(0, n1 - 1));
  const double size = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
  Eigen::VectorXd normal = Eigen::VectorXd::Zero(sd);
  if (!(a.norm() > 1e-10 * size)) return {a, normal};
  if (sd == 2) {
    normal = Eigen::Vector2d(-a[1], a[0]).normalized();
    return {a.normalized(), normal};
  }
  const Eigen::Vector3d b = (P(0, n1 - 1) - P(0, 0)) + (P(n0 - 1, n1 - 1) - P(n0 - 1, 0));
  const Eigen::Vector3d n = Eigen::Vector3d(a).cross(b);
  if (n.norm() > 1e-10 * size * a.norm()) normal = n.normalized();
  return {a.normalized(), normal};
}

// A rational Bezier element cut into pieces x pieces equal parts (pieces
// along a curve): each part's control points (n_local x dim, first
// direction fastest), by de Casteljau's algorithm on the homogeneous
// points. Each part's points hold that part (positive weights stay
// positive), closer than the whole element's do.
std::vector<Eigen::MatrixXd> bezier_parts(const std::vector<std::array<double, 4>>& homogeneous,
                                          const std::array<int, 2>& degree, int param_dim, int space_dim,
                                          std::array<int, 2> pieces_along) {
  const int pieces = pieces_along[0];
  using Row = std::vector<std::array<double, 4>>;
  // Cuts one Bezier curve's points into `pieces` equal parts: the first
  // 1/pieces split off, the rest cut again.
  auto cut = [](Row curve, int pieces) {
    std::vector<Row> parts;
    const int n = int(curve.size());
    for (int k = pieces; k > 1; --k) {
      const double t = 1.0 / k;
      Row left(size_t(n), {0, 0, 0, 0}), work = curve;
      for (int level = 0; level < n; ++level) {
        left[size_t(level)] = work[0];
        curve[size_t(n - 1 - level)] = work[size_t(n - 1 - level)];
        for (int i = 0; i + 1 < n - level; ++i)
          for (int c = 0; c < 4; ++c) work[size_t(i)][c] = (1 - t) * work[size_t(i)][c] + t * work[size_t(i + 1)][c];
      }
      parts.push_back(left);
    }
    parts.push_back(curve);
    return parts;
  };
  const int n0 = degree[0] + 1, n1 = param_dim > 1 ? degree[1] + 1 : 1;
  const int p1 = param_dim > 1 ? pieces_along[1] : 1;
  // Along the first direction, row by row: along[k][j] is row j of part k.
  std::vector<std::vector<Row>> along(static_cast<size_t>(pieces), std::vector<Row>(static_cast<size_t>(n1)));
  for (int j = 0; j < n1; ++j) {
    const Row row(homogeneous.begin() + j * n0, homogeneous.begin() + (j + 1) * n0);
    const std::vector<Row> parts = cut(row, pieces);
    for (int k = 0; k < pieces; ++k) along[size_t(k)][size_t(j)] = parts[size_t(k)];
  }
  std::vector<Eigen::MatrixXd> out;
  for (int l = 0; l < p1; ++l)
    for (int k = 0; k < pieces; ++k) out.emplace_back(n0 * n1, space_dim);
  for (int k = 0; k < pieces; ++k)
    for (int i = 0; i < n0; ++i) {
      Row column(static_cast<size_t>(n1));
      for (int j = 0; j < n1; ++j) column[size_t(j)] = along[size_t(k)][size_t(j)][size_t(i)];
      const std::vector<Row> parts = n1 > 1 ? cut(column, p1) : std::vector<Row>{column};
      for (int l = 0; l < p1; ++l)
        for (int j = 0; j < n1; ++j) {
          const std::array<double, 4>& h = parts[size_t(l)][size_t(j)];
          for (int c = 0; c < space_dim; ++c) out[size_t(k + pieces * l)](i + n0 * j, c) = h[c] / h[3];
        }
    }
  return out;
}

// How many parts bezier_parts cuts an element into along each direction
// for its parts' boxes: two, four along a direction at least twice as long
// as the other (a strip of a graded mesh), a curve in four.
std::array<int, 2> pieces_for_bounds(const Eigen::MatrixXd& points, const std::array<int, 2>& degree, int param_dim) {
  if (param_dim == 1) return {4, 1};
  const int n0 = degree[0] + 1, n1 = degree[1] + 1;
  auto P = [&](int i, int j) -> Eigen::VectorXd { return points.row(i + n0 * j).transpose(); };
  const double along0 = (P(n0 - 1, 0) - P(0, 0)).norm() + (P(n0 - 1, n1 - 1) - P(0, n1 - 1)).norm();
  const double along1 = (P(0, n1 - 1) - P(0, 0)).norm() + (P(n0 - 1, n1 - 1) - P(n0 - 1, 0)).norm();
  return {along0 >= 2 * along1 ? 4 : 2, along1 >= 2 * along0 ? 4 : 2};
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
      const auto [tangent, normal] = element_directions(be.points, e.degree, n);
      e.bounds.frame = fitted_frame(tangent, normal);
      e.bounds.hold(be.points);
      for (const Eigen::MatrixXd& part : bezier_parts(e.homogeneous, e.degree, n, int(be.points.cols()),
                                                      pieces_for_bounds(be.points, e.degree, n))) {
        Bounds b;
        const auto [part_tangent, part_normal] = element_directions(part, e.degree, n);
        b.frame = fitted_frame(part_tangent, part_normal);
        b.hold(part);
        e.parts.push_back(std::move(b));
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
  // The node's frame: its elements' mean directions, each element's turned
  // to agree with the first's (a side's parameters may run either way).
  const Bounds& first_bounds = elements_[order_[first]].bounds;
  const int sd = int(first_bounds.frame.rows());
  Eigen::VectorXd tangent = Eigen::VectorXd::Zero(sd), normal = Eigen::VectorXd::Zero(sd);
  for (int i = first; i < first + count; ++i) {
    const Eigen::MatrixXd f = elements_[order_[i]].bounds.frame;
    tangent += f.col(0).dot(first_bounds.frame.col(0)) < 0 ? Eigen::VectorXd(-f.col(0)) : Eigen::VectorXd(f.col(0));
    normal += f.col(sd - 1).dot(first_bounds.frame.col(sd - 1)) < 0 ? Eigen::VectorXd(-f.col(sd - 1))
                                                                    : Eigen::VectorXd(f.col(sd - 1));
  }
  // (Elements facing many ways, a normal sum shorter than half their
  // count: the axes.)
  Bounds bounds;
  bounds.frame = normal.norm() > 0.5 * count ? fitted_frame(tangent, normal) : Eigen::MatrixXd::Identity(sd, sd);
  for (int i = first; i < first + count; ++i) bounds.hold(elements_[order_[i]].points);
  const Eigen::VectorXd lo = bounds.lo, hi = bounds.hi;
  nodes_[id].bounds = std::move(bounds);
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
                     return elements_[a].bounds.lo[axis] + elements_[a].bounds.hi[axis] <
                            elements_[b].bounds.lo[axis] + elements_[b].bounds.hi[axis];
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

double MasterSurface::Bounds::distance(const Eigen::VectorXd& x) const {
  double aligned = 0, fitted = 0;
  const int sd = int(x.size());
  for (int a = 0; a < sd; ++a) {
    const double outside = std::max({lo[a] - x[a], 0.0, x[a] - hi[a]});
    aligned += outside * outside;
    double v = 0;
    for (int c = 0; c < sd; ++c) v += frame(c, a) * x[c];
    const double across = std::max({frame_lo[a] - v, 0.0, v - frame_hi[a]});
    fitted += across * across;
  }
  return std::sqrt(std::max(aligned, fitted));
}

double MasterSurface::Element::distance_bound(const Eigen::VectorXd& x, double beyond) const {
  const double whole = bounds.distance(x);
  if (whole >= beyond || parts.empty()) return whole;
  double nearest_part = std::numeric_limits<double>::infinity();
  for (const Bounds& b : parts) {
    nearest_part = std::min(nearest_part, b.distance(x));
    if (nearest_part <= whole) return whole;
  }
  return std::max(whole, nearest_part);
}

void MasterSurface::Bounds::hold(const Eigen::MatrixXd& points) {
  const Eigen::MatrixXd along = points * frame;  // (coordinates along each column)
  if (lo.size() == 0) {
    lo = points.colwise().minCoeff().transpose();
    hi = points.colwise().maxCoeff().transpose();
    frame_lo = along.colwise().minCoeff().transpose();
    frame_hi = along.colwise().maxCoeff().transpose();
    return;
  }
  lo = lo.cwiseMin(points.colwise().minCoeff().transpose());
  hi = hi.cwiseMax(points.colwise().maxCoeff().transpose());
  frame_lo = frame_lo.cwiseMin(along.colwise().minCoeff().transpose());
  frame_hi = frame_hi.cwiseMax(along.colwise().maxCoeff().transpose());
}

std::optional<MasterPoint> MasterSurface::project(const Eigen::VectorXd& x, int* candidates) const {
  const Clock clock(counters_);
  ++counters_.queries;
  if (nodes_.empty()) return std::nullopt;
  const Element* best_element = nullptr;
  OnElement best;
  double bound = std::numeric_limits<double>::infinity();
  // A point on the surface to round-off: no other element can be nearer.
  const double on_surface = 1e-14 * (nodes_[0].bounds.hi - nodes_[0].bounds.lo).norm();
  // Best first: the pending nodes and elements in a heap by their bound,
  // Newton on an element only when no pending bound is lower, and done when
  // the lowest is no nearer than the best point found. (The order does not
  // depend on the thread: each query on its own.)
  struct Pending {
    double bound;
    int node, element;  // a node, or (node -1) an element
    bool operator<(const Pending& o) const { return bound > o.bound; }  // (min-heap)
  };
  thread_local std::vector<Pending> heap;
  heap.clear();
  heap.push_back({nodes_[0].bounds.distance(x), 0, -1});
  auto push = [&](Pending p) {
    if (p.bound >= bound) return;
    heap.push_back(p);
    std::push_heap(heap.begin(), heap.end());
  };
  while (!heap.empty() && heap.front().bound < bound) {
    std::pop_heap(heap.begin(), heap.end());
    const Pending next = heap.back();
    heap.pop_back();
    if (next.node < 0) {
      const Element& e = elements_[next.element];
      ++counters_.candidates;
      if (candidates) ++*candidates;
      OnElement nearest = nearest_on_element(e, x);
      if (nearest.distance < bound) {
        bound = nearest.distance;
        best = std::move(nearest);
        best_element = &e;
        if (bound <= on_surface) return master_point(e, best, x);
      }
      continue;
    }
    const Node& node = nodes_[next.node];
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i)
        push({elements_[order_[i]].distance_bound(x, bound), -1, order_[i]});
      continue;
    }
    push({nodes_[node.left].bounds.distance(x), node.left, -1});
    push({nodes_[node.right].bounds.distance(x), node.right, -1});
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
