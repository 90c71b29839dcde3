// SPDX-License-Identifier: BSD-3-Clause
#include "model/case_body.hpp"

#include <fmt/format.h>

#include "engine/geometry/shapes.hpp"
#include "engine/spline/split.hpp"

namespace igac {

Geometry case_geometry(const CaseSpec& spec) {
  if (!spec.geometry_file.empty())  // a file's body: case_body
    throw InputError(fmt::format("{}: [geometry] file: not a built-in shape", spec.path));
  try {
    if (const ShapeType* kind = find_shape_type(spec.shape)) {
      if (!spec.shape_values.empty()) return kind->make(spec.shape_values);
      // A CaseSpec made in code may give only the named fields.
      const ShapeValues v{{"radius", {spec.radius}},
                          {"inner_radius", {spec.inner_radius}},
                          {"outer_radius", {spec.outer_radius}},
                          {"size", spec.size}};
      return kind->make(v);
    }
  } catch (const SplineError& e) {
    throw InputError(fmt::format("{}: [geometry] {}", spec.path, e.what()));
  } catch (const std::out_of_range&) {
    throw InputError(fmt::format("{}: [geometry] size: too few entries for a {}", spec.path, spec.shape));
  }
  throw InputError(fmt::format("{}: [geometry] shape: unknown shape \"{}\"", spec.path, spec.shape));
}

MultiPatch case_body(const CaseSpec& spec) {
  if (!spec.geometry_file.empty()) {
    if (!spec.file_body)
      throw InputError(fmt::format("{}: [geometry] file {}: the case names a geometry file but holds no patches "
                                   "(read it with io/case_file's read_case)", spec.path, spec.geometry_file));
    return *spec.file_body;  // as the user wrote it
  }
  return single_patch_body(case_geometry(spec).patch);
}

}  // namespace igac
