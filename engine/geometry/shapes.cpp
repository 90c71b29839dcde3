// SPDX-License-Identifier: BSD-3-Clause
// Face lookup shared by every shape, and the registry of built-in shapes:
// one file per shape in shapes/, one line here.
#include "engine/geometry/shapes.hpp"

#include "engine/geometry/side_names.hpp"

#include <fmt/format.h>

namespace igac {

namespace {
const ShapeType* const kShapes[] = {
    &quarter_disc_shape(),
    &sphere_octant_shape(),
    &quarter_annulus_shape(),
    &rectangle_shape(),
    &box_shape(),
};
}  // namespace

std::span<const ShapeType* const> shape_types() { return kShapes; }

const ShapeType* find_shape_type(std::string_view name) {
  for (const ShapeType* t : kShapes)
    if (t->name == name) return t;
  return nullptr;
}

std::optional<PatchSide> parametric_side(const std::string& name, int patches, int param_dim) {
  static const char* dirs = "uvw";
  for (int k = 0; k < patches; ++k)
    for (int d = 0; d < param_dim; ++d)
      for (int e = 0; e < 2; ++e) {
        const Face f{d, e == 1};
        const std::string parametric = fmt::format("{}{}", dirs[d], e);
        const std::string prefix = fmt::format("{}:", k);
        if (name == prefix + parametric || name == prefix + gismo_side_name(gismo_side_of(f)) ||
            (patches == 1 && name == parametric))
          return PatchSide{k, f};
      }
  return std::nullopt;
}

std::vector<std::string> parametric_side_names(int patches, int param_dim) {
  std::vector<std::string> out;
  static const char* dirs = "uvw";
  if (patches == 1)
    for (int d = 0; d < param_dim; ++d)
      for (int e = 0; e < 2; ++e) out.push_back(fmt::format("{}{}", dirs[d], e));
  for (int k = 0; k < patches; ++k)
    for (int s = 1; s <= 2 * param_dim; ++s) out.push_back(fmt::format("{}:{}", k, gismo_side_name(s)));
  return out;
}

std::optional<std::vector<PatchSide>> find_faces(const Geometry& g, const std::string& name) {
  if (auto it = g.faces.find(name); it != g.faces.end()) return it->second;
  if (auto side = parametric_side(name, 1, g.patch.param_dim())) return std::vector<PatchSide>{*side};
  return std::nullopt;
}

std::vector<std::string> face_names(const Geometry& g) {
  std::vector<std::string> out;
  for (const auto& [k, v] : g.faces) out.push_back(k);
  for (auto& n : parametric_side_names(1, g.patch.param_dim())) out.push_back(std::move(n));
  return out;
}

}  // namespace igac
