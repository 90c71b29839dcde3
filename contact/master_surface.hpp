// SPDX-License-Identifier: BSD-3-Clause
// The master side of a contact between two deformable bodies: one or more
// patch sides of a body, in their current position, and the closest-point
// projection of a point of space onto them.  Mortar contact (De Lorenzis,
// Temizer, Wriggers and Zavarise 2011; 4C's dual mortar) integrates the
// weighted gap on the slave face; at every slave quadrature point it needs
// the master point nearest to it, its parameters (to couple the master's
// control points) and the master's outward normal there.
//
// The search must not visit every master element per slave point: the
// master's elements are kept in a bounding-volume hierarchy (a tree over
// the rational Bezier control points of each element, which contain the
// element by the convex hull property, positive weights).  Each element
// and each node holds its points in two boxes, one axis-aligned and one in
// a frame fitted to the surface there (thin across a curved surface, where
// the axis-aligned box is as thick as the element is long); an element
// also has the boxes of its parts (cut by de Casteljau), thin where a long
// curved element's own box is as thick as its sagitta.  A query takes
// pending nodes and elements best bound first and stops when none is
// nearer than the best point found: O(log n) nodes per point, Newton on
// about one element for a point near the surface, a few far from it
// (docs/design.md).  On each candidate element the projection is
// Newton's method on the element's Bezier coordinates (Gauss-Newton first),
// kept inside the element, started at its centre; the element is evaluated
// in its Bezier form (Bernstein polynomials, no knot search).  update()
// moves the surface (large deformation: every Newton iteration) and
// rebuilds the boxes and the tree.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <atomic>
#include <optional>
#include <vector>

#include "engine/body.hpp"

namespace igac {

struct MasterPoint {
  int side = 0;               // index into the master's sides
  int element = 0;            // element of that side's face patch
  Eigen::VectorXd xi;         // parameters on the face patch
  Eigen::VectorXd x;          // the point (current position)
  Eigen::VectorXd normal;     // outward unit normal of the master body there
  double distance = 0;        // |x_query - x|
  double gap = 0;             // (x_query - x) . normal: positive outside the master
};

class MasterSurface {
 public:
  // The sides of `body` that form the master surface, at the reference
  // position.  Keeps no reference to `body`.
  MasterSurface(const Body& body, const std::vector<PatchSide>& sides);

  // Moves the surface: `u` is the displacement per body control point
  // (n_cp x dim, body numbering); rebuilds the element boxes and the tree.
  void update(const Eigen::MatrixXd& u);

  // The master point nearest to `x` (nullopt for an empty surface, or an x
  // that is not finite).
  // `candidates`: += the elements it ran Newton on (the search's cost).
  // Safe to call from several threads at once.
  std::optional<MasterPoint> project(const Eigen::VectorXd& x, int* candidates = nullptr) const;
  // The same by trying every element: the reference the tree is checked against.
  std::optional<MasterPoint> project_by_every_element(const Eigen::VectorXd& x) const;

  int num_elements() const { return int(elements_.size()); }
  // Body numbers of side s's control points, in its face patch's numbering.
  int num_sides() const { return int(sides_.size()); }
  const std::vector<int>& side_control_points(int s) const { return sides_[s].cps; }
  const NurbsPatch& side_patch(int s) const { return sides_[s].current; }
  // What the search has cost since construction (or reset): project()
  // calls, the elements they ran Newton on, and the seconds spent in them,
  // summed over threads (bench/two_body_search).
  struct SearchCounters {
    long queries = 0, candidates = 0;
    double seconds = 0;
  };
  SearchCounters counters() const { return {counters_.queries, counters_.candidates, counters_.seconds}; }
  void reset_counters() { counters_ = {}; }

 private:
  struct Side {
    PatchSide side;
    NurbsPatch reference, current;
    std::vector<int> cps;
  };
  // Two boxes that hold a set of control points, the distance to either a
  // lower bound of the distance to the surface they hold: axis-aligned, and
  // in an orthonormal frame (columns: the tangent directions, then the
  // normal; the axes where no frame fits).
  struct Bounds {
    using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;  // (held inline: read per query)
    Vector lo, hi;
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3> frame;
    Vector frame_lo, frame_hi;
    // The larger of the two boxes' distances from x (0 inside both).
    double distance(const Eigen::VectorXd& x) const;
    // Grows both boxes to hold points (rows), the frame kept.
    void hold(const Eigen::MatrixXd& points);
  };
  struct Element {
    int side = 0, index = 0;
    Eigen::VectorXd lo, hi;              // parameter box
    Bounds bounds;                       // in space
    std::vector<Bounds> parts;           // of its parts (bezier_parts): tighter
    // A lower bound of the distance from x to the element: the larger of
    // its boxes' distance and its nearest part's, or (enough to prune it)
    // the boxes' alone when that is beyond `beyond`.
    double distance_bound(const Eigen::VectorXd& x, double beyond) const;
    std::array<int, 2> degree{0, 0};
    Eigen::MatrixXd points;              // rational Bezier control points (n_local x dim), first direction fastest
    Eigen::VectorXd weights;
    // The same in homogeneous form, 4 numbers per point: w x, w y, w z (0 in
    // 2D), w; what evaluate() sums, in fixed-width loops.
    std::vector<std::array<double, 4>> homogeneous;
  };
  struct Node {
    Bounds bounds;
    int left = -1, right = -1;           // children, or -1 for a leaf
    int first = 0, count = 0;            // a leaf's range in order_
  };
  void build_elements();
  int build_tree(int first, int count);
  // Newton on one element (param_dim N, space_dim SD known at compile time:
  // the projection is most of a two-body run's contact time).
  struct OnElement;
  template <int N, int SD>
  OnElement nearest_on_element(const Element& e, const Eigen::VectorXd& x) const;
  OnElement nearest_on_element(const Element& e, const Eigen::VectorXd& x) const;
  MasterPoint master_point(const Element& e, const OnElement& nearest, const Eigen::VectorXd& x) const;

  std::vector<Side> sides_;
  std::vector<Element> elements_;
  std::vector<int> order_;  // element indices, grouped by leaf
  std::vector<Node> nodes_;
  // SearchCounters, added to by concurrent queries.
  struct AtomicCounters {
    std::atomic<long> queries{0}, candidates{0};
    std::atomic<double> seconds{0};
    AtomicCounters() = default;
    AtomicCounters(const AtomicCounters& o) : queries(o.queries.load()), candidates(o.candidates.load()), seconds(o.seconds.load()) {}
    AtomicCounters& operator=(const AtomicCounters& o) {
      queries = o.queries.load(), candidates = o.candidates.load(), seconds = o.seconds.load();
      return *this;
    }
  };
  mutable AtomicCounters counters_;
};

}  // namespace igac
