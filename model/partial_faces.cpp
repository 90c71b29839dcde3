// SPDX-License-Identifier: BSD-3-Clause
#include "model/partial_faces.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <stdexcept>

#include "engine/geometry/side_names.hpp"

namespace igac {

PatchSide side_in_file(const Model& m, PatchSide s) {
  if (s.face.direction == 0 && std::count(m.reoriented_patches.begin(), m.reoriented_patches.end(), s.patch))
    s.face.at_end = !s.face.at_end;
  return s;
}

std::vector<PatchSide> sides_of_pieces(const Model& m, const PatchSide& s) {
  const auto it = m.cut_patches.find(s.patch);
  if (it == m.cut_patches.end()) return {s};
  return piece_sides(it->second, m.spec.dim(), s.face);
}

namespace {

std::string where_side(const Model& m, const PartialFaceSpec& pf, const char* key = "side") {
  return m.spec.where({.table = "faces." + pf.name, .key = key});
}

// The side a partial face lies on, when it is a side of this body (in the
// model's numbers, before any cut).
std::optional<PatchSide> side_on_body(const Model& m, const BodySpec& b, int offset, int file_patches, int param_dim,
                                      const PartialFaceSpec& pf) {
  const std::string prefix = b.body_name.empty() ? "" : b.body_name + ":";
  if (!pf.side.starts_with(prefix)) return std::nullopt;
  if (std::any_of(m.spec.partial_faces.begin(), m.spec.partial_faces.end(),
                  [&](const PartialFaceSpec& other) { return other.name == pf.side; }))
    throw InputError(fmt::format("{}: [faces.{}] side: '{}' is itself part of a side: give the range on the side "
                                 "it lies on", where_side(m, pf), pf.name, pf.side));
  if (const auto it = m.faces.find(pf.side); it != m.faces.end()) {  // a name the shape gives
    if (it->second.size() != 1)
      throw InputError(fmt::format("{}: [faces.{}] side: '{}' is {} sides; a range lies along one: name it as "
                                   "PATCH:SIDE",
                                   where_side(m, pf), pf.name, pf.side, it->second.size()));
    if (it->second.front().patch < offset) return std::nullopt;
    return it->second.front();
  }
  if (auto side = parametric_side(pf.side.substr(prefix.size()), file_patches, param_dim)) {
    side->patch += offset;
    return side_in_file(m, *side);
  }
  return std::nullopt;
}

}  // namespace

void cut_partial_faces(Model& m, const BodySpec& body, int offset, int file_patches, std::vector<NurbsPatch>& own,
                       std::vector<PatchInterface>& interfaces) {
  const int param_dim = own.front().param_dim();
  struct OnThisBody {
    const PartialFaceSpec* spec;
    PatchSide side;  // in the model's numbers
    std::vector<std::array<double, 2>> range;  // along the side, in the patch's parameters
  };
  std::vector<OnThisBody> parts;
  std::vector<PatchCuts> cuts;
  for (const PartialFaceSpec& pf : m.spec.partial_faces) {
    const auto side = side_on_body(m, body, offset, file_patches, param_dim, pf);
    if (!side) continue;
    OnThisBody part{&pf, *side, pf.range};
    const std::vector<int> along = face_directions(param_dim, side->face);
    PatchCuts cut{side->patch - offset, {}};
    const bool backwards =
        std::count(m.reoriented_patches.begin(), m.reoriented_patches.end(), side->patch) > 0;
    for (size_t i = 0; i < along.size(); ++i) {
      auto& r = part.range[i];
      if (backwards && along[i] == 0) r = {1 - r[1], 1 - r[0]};  // the file's u runs the other way here
      for (double t : r)
        if (t > 0 && t < 1) cut.at[size_t(along[i])].push_back(t);
    }
    cuts.push_back(cut);
    parts.push_back(std::move(part));
  }
  if (parts.empty()) return;

  std::vector<std::vector<PatchPiece>> pieces;
  try {
    pieces = cut_patches(own, interfaces, cuts);
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("{}: [faces.{}] range: {}", where_side(m, *parts.front().spec, "range"),
                                 parts.front().spec->name, e.what()));
  }
  for (size_t k = 0; k < pieces.size(); ++k) {
    if (pieces[k].size() == 1) continue;
    for (PatchPiece& piece : pieces[k]) piece.patch += offset;
    m.cut_patches[offset + int(k)] = pieces[k];
  }
  // The body's named faces (the shape's) now stand for their pieces' sides.
  for (auto& [name, sides] : m.faces) {
    if (sides.empty() || sides.front().patch < offset) continue;
    std::vector<PatchSide> expanded;
    for (const PatchSide& s : sides)
      for (const PatchSide& piece : sides_of_pieces(m, s)) expanded.push_back(piece);
    sides = std::move(expanded);
  }
  for (const OnThisBody& part : parts) {
    if (m.faces.count(part.spec->name))
      throw InputError(fmt::format("{}: [faces] {}: the name is taken by a face of the body",
                                   m.spec.where({.table = "faces", .key = part.spec->name}), part.spec->name));
    const auto it = m.cut_patches.find(part.side.patch);
    m.faces[part.spec->name] = it == m.cut_patches.end()
                                   ? std::vector<PatchSide>{part.side}
                                   : piece_sides_within(it->second, param_dim, part.side.face, part.range);
  }
}

void check_partial_faces_found(const Model& m) {
  for (const PartialFaceSpec& pf : m.spec.partial_faces)
    if (!m.faces.count(pf.name))
      throw InputError(fmt::format("{}: [faces.{}] side: unknown side '{}' (known: {})", where_side(m, pf), pf.name,
                                   pf.side, fmt::join(face_names(m), ", ")));
}

}  // namespace igac
