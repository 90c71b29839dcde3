// SPDX-License-Identifier: BSD-3-Clause
#include "model/case_body.hpp"

#include <fmt/format.h>

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
      // A CaseSpec made in code may give only the named fields.
      const ShapeValues v{{"radius", {body.radius}},
                          {"inner_radius", {body.inner_radius}},
                          {"outer_radius", {body.outer_radius}},
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

NurbsPatch translated(const NurbsPatch& p, const std::vector<double>& by) {
  if (by.empty()) return p;
  std::vector<KnotVector> knots;
  for (int d = 0; d < p.param_dim(); ++d) knots.push_back(p.knots(d));
  Eigen::MatrixXd X = p.points();
  for (int c = 0; c < X.cols() && c < int(by.size()); ++c) X.col(c).array() += by[size_t(c)];
  return NurbsPatch(std::move(knots), std::move(X), p.weights());
}

}  // namespace

Geometry body_geometry(const CaseSpec& spec, const BodySpec& body) {
  Geometry g = shape_geometry(spec, body);
  g.patch = translated(g.patch, body.translate);
  return g;
}

MultiPatch body_patches(const CaseSpec& spec, const BodySpec& body) {
  if (!body.geometry_file.empty()) {
    if (!body.file_body)
      throw InputError(fmt::format("{}: {} file {}: the case names a geometry file but holds no patches "
                                   "(read it with io/case_file's read_case)", spec.where(body, "geometry", "file"), table(body),
                                   body.geometry_file));
    MultiPatch mp = *body.file_body;  // as the user wrote it, placed where the case puts it
    for (NurbsPatch& p : mp.patches) p = translated(p, body.translate);
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
