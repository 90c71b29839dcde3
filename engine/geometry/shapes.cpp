// Face lookup shared by every shape, and the registry of built-in shapes:
// one file per shape in shapes/, one line here.
#include "engine/geometry/shapes.hpp"

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

std::optional<std::vector<PatchSide>> find_faces(const Geometry& g, const std::string& name) {
  if (auto it = g.faces.find(name); it != g.faces.end()) return it->second;
  static const char* dirs = "uvw";
  static const char* sides[] = {"west", "east", "south", "north", "front", "back"};  // G+Smo's sides 1..6
  for (int d = 0; d < g.patch.param_dim(); ++d)
    for (int e = 0; e < 2; ++e) {
      const std::string parametric = fmt::format("{}{}", dirs[d], e);
      // u0 ... w1, and PATCH:SIDE as in geometry files (the body is patch 0)
      if (name == parametric || name == "0:" + parametric || name == std::string("0:") + sides[2 * d + e])
        return std::vector<PatchSide>{PatchSide{0, Face{d, e == 1}}};
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
