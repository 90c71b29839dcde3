#include "engine/geometry/shapes.hpp"

#include <cmath>
#include <fmt/format.h>

namespace igac {
namespace {

const double kHalfSqrt2 = std::sqrt(0.5);

KnotVector bezier(int p) { return KnotVector::uniform(p, 1); }

void check_positive(double v, const char* what) {
  if (!(v > 0) || !std::isfinite(v)) throw SplineError(fmt::format("{} must be positive, got {}", what, v));
}

}  // namespace

Geometry quarter_disc(double R) {
  check_positive(R, "radius");
  const double d = 0.5 * R;  // the straight corner D = (0, -d)
  Eigen::MatrixXd P(9, 2);
  Eigen::VectorXd w = Eigen::VectorXd::Ones(9);
  // row v = 0: the arc (exact circle)
  P.row(0) << 0, -R;
  P.row(1) << R, -R;
  w[1] = kHalfSqrt2;
  P.row(2) << R, 0;
  // row v = 1/2
  P.row(3) << 0, -(R + d) / 2;
  P.row(4) << 0.6 * R, -0.6 * R;  // chosen for the most even det J (min/max)
  P.row(5) << R / 2, 0;
  // row v = 1: x = 0 from D to the centre
  P.row(6) << 0, -d;
  P.row(7) << 0, -d / 2;
  P.row(8) << 0, 0;
  Geometry g{NurbsPatch({bezier(2), bezier(2)}, P, w), {}};
  g.faces["curved"] = {Face{1, false}};
  g.faces["top"] = {Face{0, true}};
  g.faces["left"] = {Face{0, false}, Face{1, true}};
  return g;
}

Geometry sphere_octant(double R) {
  // Revolve the quarter disc, placed in the plane y = 0 as (x, 0, z) with
  // z = its y, about the x axis by 90 degrees (Piegl & Tiller 8.5): the
  // rotation is the third parametric direction, run from the plane z = 0
  // (w = 0) to the plane y = 0 (w = 1) so that det J > 0.
  const Geometry disc = quarter_disc(R);
  const NurbsPatch& d = disc.patch;
  const int n = d.num_control_points();
  Eigen::MatrixXd P(3 * n, 3);
  Eigen::VectorXd w(3 * n);
  const double ring_weight[3] = {1.0, kHalfSqrt2, 1.0};
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < n; ++a) {
      const double x = d.points()(a, 0), z = d.points()(a, 1);  // z <= 0
      // k = 0: (x, -z, 0); k = 1: (x, -z, z) (corner of the control square); k = 2: (x, 0, z)
      const Eigen::Vector3d q = k == 0 ? Eigen::Vector3d(x, -z, 0) : k == 1 ? Eigen::Vector3d(x, -z, z) : Eigen::Vector3d(x, 0, z);
      P.row(k * n + a) = q.transpose();
      w[k * n + a] = d.weights()[a] * ring_weight[k];
    }
  Geometry g{NurbsPatch({d.knots(0), d.knots(1), bezier(2)}, P, w), {}};
  g.faces["curved"] = {Face{1, false}};
  g.faces["top"] = {Face{2, false}};                 // z = 0
  g.faces["back"] = {Face{2, true}};                 // y = 0
  g.faces["left"] = {Face{0, false}, Face{1, true}}; // x = 0
  g.faces["axis"] = {Face{0, true}};                 // collapsed onto the x axis
  return g;
}

Geometry quarter_annulus(double a, double b) {
  check_positive(a, "inner radius");
  check_positive(b, "outer radius");
  if (!(b > a)) throw SplineError(fmt::format("outer radius {} must exceed inner radius {}", b, a));
  // u radial (degree 1), v along the angle from the x axis (degree 2): det J > 0.
  Eigen::MatrixXd P(6, 2);
  Eigen::VectorXd w(6);
  P << a, 0, b, 0, a, a, b, b, 0, a, 0, b;
  w << 1, 1, kHalfSqrt2, kHalfSqrt2, 1, 1;
  Geometry g{NurbsPatch({bezier(1), bezier(2)}, P, w), {}};
  g.faces["inner"] = {Face{0, false}};
  g.faces["outer"] = {Face{0, true}};
  g.faces["bottom"] = {Face{1, false}};
  g.faces["left"] = {Face{1, true}};
  return g;
}

Geometry rectangle(double lx, double ly) {
  check_positive(lx, "rectangle width");
  check_positive(ly, "rectangle height");
  Eigen::MatrixXd P(4, 2);
  P << 0, 0, lx, 0, 0, ly, lx, ly;
  Geometry g{NurbsPatch({bezier(1), bezier(1)}, P, Eigen::VectorXd::Ones(4)), {}};
  g.faces["left"] = {Face{0, false}};
  g.faces["right"] = {Face{0, true}};
  g.faces["bottom"] = {Face{1, false}};
  g.faces["top"] = {Face{1, true}};
  return g;
}

Geometry box(double lx, double ly, double lz) {
  check_positive(lx, "box length x");
  check_positive(ly, "box length y");
  check_positive(lz, "box length z");
  Eigen::MatrixXd P(8, 3);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) P.row(i + 2 * j + 4 * k) << i * lx, j * ly, k * lz;
  Geometry g{NurbsPatch({bezier(1), bezier(1), bezier(1)}, P, Eigen::VectorXd::Ones(8)), {}};
  g.faces["left"] = {Face{0, false}};
  g.faces["right"] = {Face{0, true}};
  g.faces["front"] = {Face{1, false}};
  g.faces["back"] = {Face{1, true}};
  g.faces["bottom"] = {Face{2, false}};
  g.faces["top"] = {Face{2, true}};
  return g;
}

std::optional<std::vector<Face>> find_faces(const Geometry& g, const std::string& name) {
  if (auto it = g.faces.find(name); it != g.faces.end()) return it->second;
  static const char* dirs = "uvw";
  static const char* sides[] = {"west", "east", "south", "north", "front", "back"};  // G+Smo's sides 1..6
  for (int d = 0; d < g.patch.param_dim(); ++d)
    for (int e = 0; e < 2; ++e) {
      const std::string parametric = fmt::format("{}{}", dirs[d], e);
      // u0 ... w1, and PATCH:SIDE as in geometry files (the body is patch 0)
      if (name == parametric || name == "0:" + parametric || name == std::string("0:") + sides[2 * d + e])
        return std::vector<Face>{Face{d, e == 1}};
    }
  return std::nullopt;
}

std::vector<std::string> face_names(const Geometry& g) {
  std::vector<std::string> out;
  for (const auto& [k, v] : g.faces) out.push_back(k);
  static const char* dirs = "uvw";
  for (int d = 0; d < g.patch.param_dim(); ++d)
    for (int e = 0; e < 2; ++e) out.push_back(fmt::format("{}{}", dirs[d], e));
  static const char* sides[] = {"west", "east", "south", "north", "front", "back"};
  for (int s = 0; s < 2 * g.patch.param_dim(); ++s) out.push_back(fmt::format("0:{}", sides[s]));
  return out;
}

}  // namespace igac
