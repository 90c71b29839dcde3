// SPDX-License-Identifier: BSD-3-Clause
#include "model/case_body.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "engine/geometry/shapes.hpp"
#include "engine/spline/split.hpp"

namespace igac {

namespace {
// "[geometry]", or "[body.geometry] (body 'roller')" for one of several.
std::string table(const BodySpec& body) {
  return body.body_name.empty() ? "[geometry]" : fmt::format("[body.geometry] (body '{}')", body.body_name);
}

Geometry shape_geometry(const CaseSpec& spec, const BodySpec& body) {
  if (!body.geometry_file.empty())  // a file's body: body_patches
    throw InputError(fmt::format("{}: {} file: not a built-in shape", spec.where(body, "geometry", "file"), table(body)));
  try {
    if (const ShapeType* kind = find_shape_type(body.shape)) {
      if (!body.shape_values.empty()) return kind->make(body.shape_values);
      // A CaseSpec made in code may give only the named fields (its radii
      // are the body's as it stands, after `scale`, which placed() applies).
      const ShapeValues v{{"radius", {body.radius / body.scale}},
                          {"inner_radius", {body.inner_radius / body.scale}},
                          {"outer_radius", {body.outer_radius / body.scale}},
                          {"size", body.size}};
      return kind->make(v);
    }
  } catch (const SplineError& e) {
    throw InputError(fmt::format("{}: {} {}", spec.where(body, "geometry", "shape"), table(body), e.what()));
  } catch (const std::out_of_range&) {
    throw InputError(fmt::format("{}: {} size: too few entries for a {}", spec.where(body, "geometry", "size"),
                                 table(body), body.shape));
  }
  throw InputError(fmt::format("{}: {} shape: unknown shape \"{}\"", spec.where(body, "geometry", "shape"), table(body),
                               body.shape));
}

// The patch's control points moved by the body's transforms, in order:
// scale, mirror, rotate, translate.  Affine maps of the control points are
// exact for NURBS (weights unchanged).
NurbsPatch placed(const NurbsPatch& p, const BodySpec& body) {
  const bool moved = body.scale != 1 || !body.mirror.empty() || !body.rotate.empty() || !body.translate.empty();
  if (!moved) return p;
  const int dim = p.space_dim();
  Eigen::MatrixXd A = body.scale * Eigen::MatrixXd::Identity(dim, dim);
  for (int axis : body.mirror) A.row(axis) *= -1;
  const auto turn = [dim](int axis, double degrees) {  // about the origin (2D: axis 2, the plane's normal)
    const double a = degrees * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
    Eigen::MatrixXd R = Eigen::MatrixXd::Identity(dim, dim);
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;  // the plane of the turn, counter-clockwise seen from +axis
    R(i, i) = c, R(i, j) = -s, R(j, i) = s, R(j, j) = c;
    return R;
  };
  if (dim == 2 && !body.rotate.empty()) A = turn(2, body.rotate[0]) * A;
  if (dim == 3)
    for (int axis = 0; axis < int(body.rotate.size()); ++axis) A = turn(axis, body.rotate[size_t(axis)]) * A;
  Eigen::MatrixXd X = p.points() * A.transpose();
  for (int c = 0; c < X.cols() && c < int(body.translate.size()); ++c) X.col(c).array() += body.translate[size_t(c)];
  std::vector<KnotVector> knots;
  for (int d = 0; d < p.param_dim(); ++d) knots.push_back(p.knots(d));
  return NurbsPatch(std::move(knots), std::move(X), p.weights());
}

}  // namespace

Geometry body_geometry(const CaseSpec& spec, const BodySpec& body) {
  Geometry g = shape_geometry(spec, body);
  g.patch = placed(g.patch, body);
  return g;
}

MultiPatch body_patches(const CaseSpec& spec, const BodySpec& body) {
  if (!body.geometry_file.empty()) {
    if (!body.file_body)
      throw InputError(fmt::format("{}: {} file {}: the case names a geometry file but holds no patches "
                                   "(read it with io/case_file's read_case)", spec.where(body, "geometry", "file"), table(body),
                                   body.geometry_file));
    MultiPatch mp = *body.file_body;  // as the user wrote it, placed where the case puts it
    for (NurbsPatch& p : mp.patches) p = placed(p, body);
    return mp;
  }
  return single_patch_body(body_geometry(spec, body).patch);
}

MultiPatch case_body(const CaseSpec& spec) {
  MultiPatch all;
  for (const BodySpec& b : spec.body_list()) {
    MultiPatch one = body_patches(spec, b);
    const int offset = int(all.patches.size());
    auto shift = [offset](PatchSide s) {
      s.patch += offset;
      return s;
    };
    for (auto& p : one.patches) all.patches.push_back(std::move(p));
    for (const PatchInterface& itf : one.interfaces) all.interfaces.push_back({shift(itf.first), shift(itf.second)});
    for (const PatchSide& s : one.boundary) all.boundary.push_back(shift(s));
  }
  return all;
}

}  // namespace igac
