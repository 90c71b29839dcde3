// SPDX-License-Identifier: BSD-3-Clause
#include "engine/geometry/patch_partition.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>

#include "engine/spline/split.hpp"

namespace igac {

namespace {

// The corners of a side (2^(param_dim - 1) points).
std::vector<Eigen::VectorXd> side_corners(const NurbsPatch& p, const Face& f) {
  const int n = p.param_dim() - 1;
  std::vector<Eigen::VectorXd> out;
  for (int c = 0; c < (1 << n); ++c) {
    std::vector<int> bits(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) bits[size_t(i)] = (c >> i) & 1;
    out.push_back(face_corner(p, f, bits));
  }
  return out;
}

// Two sides coincide: every corner of one is a corner of the other.
bool same_corners(const NurbsPatch& a, const Face& fa, const NurbsPatch& b, const Face& fb, double tol) {
  const auto ca = side_corners(a, fa), cb = side_corners(b, fb);
  return std::all_of(ca.begin(), ca.end(), [&](const Eigen::VectorXd& x) {
    return std::any_of(cb.begin(), cb.end(), [&](const Eigen::VectorXd& y) { return (x - y).norm() <= tol; });
  });
}

// The piece touches side `face` of the patch it was cut from.
bool on_side(const PatchPiece& piece, const Face& face) {
  const auto& r = piece.box[size_t(face.direction)];
  return face.at_end ? r[1] == 1.0 : r[0] == 0.0;
}

// The pieces of `patch` cut at the sorted fractions `at`: pieces of each
// direction in turn, the first piece the one at the start of every range.
std::vector<std::pair<NurbsPatch, PatchPiece>> pieces_of(const NurbsPatch& patch, const PatchCuts& cuts) {
  PatchPiece whole;
  for (auto& r : whole.box) r = {0.0, 1.0};
  std::vector<std::pair<NurbsPatch, PatchPiece>> pieces{{patch, whole}};
  for (int d = 0; d < patch.param_dim(); ++d) {
    if (cuts.at[size_t(d)].empty()) continue;
    const double a = patch.knots(d).first(), b = patch.knots(d).last();
    std::vector<std::pair<NurbsPatch, PatchPiece>> next;
    for (auto& [rest_patch, rest_box] : pieces) {
      NurbsPatch rest = rest_patch;
      PatchPiece box = rest_box;
      for (double c : cuts.at[size_t(d)]) {  // split_patch keeps the parameters: the value is the same in every piece
        auto [left, right] = split_patch(rest, d, a + c * (b - a));
        PatchPiece left_box = box;
        left_box.box[size_t(d)] = {box.box[size_t(d)][0], c};
        box.box[size_t(d)][0] = c;
        next.emplace_back(std::move(left), left_box);
        rest = std::move(right);
      }
      next.emplace_back(std::move(rest), box);
    }
    pieces = std::move(next);
  }
  for (auto& piece : pieces) piece.first = normalised(piece.first);
  return pieces;
}

}  // namespace

std::vector<PatchSide> piece_sides(const std::vector<PatchPiece>& pieces, int param_dim, const Face& face) {
  return piece_sides_within(pieces, param_dim, face, std::vector<std::array<double, 2>>(size_t(param_dim - 1), {0.0, 1.0}));
}

std::vector<PatchSide> piece_sides_within(const std::vector<PatchPiece>& pieces, int param_dim, const Face& face,
                                          const std::vector<std::array<double, 2>>& range) {
  const std::vector<int> along = face_directions(param_dim, face);
  std::vector<PatchSide> out;
  for (const PatchPiece& piece : pieces) {
    if (!on_side(piece, face)) continue;
    bool inside = true;
    for (size_t i = 0; i < along.size(); ++i) {
      const auto& r = piece.box[size_t(along[i])];
      inside = inside && r[0] >= range[i][0] && r[1] <= range[i][1];
    }
    if (inside) out.emplace_back(piece.patch, face);
  }
  return out;
}

std::vector<std::vector<PatchPiece>> cut_patches(std::vector<NurbsPatch>& patches,
                                                 std::vector<PatchInterface>& interfaces,
                                                 const std::vector<PatchCuts>& cuts) {
  const int n = int(patches.size());
  std::vector<PatchCuts> merged(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) merged[size_t(k)].patch = k;
  for (const PatchCuts& c : cuts) {
    if (c.patch < 0 || c.patch >= n) throw std::invalid_argument(fmt::format("there is no patch {} to cut", c.patch));
    for (int d = 0; d < 3; ++d)
      for (double t : c.at[size_t(d)]) {
        if (!(t > 0 && t < 1) || d >= patches[size_t(c.patch)].param_dim())
          throw std::invalid_argument(fmt::format("a cut at {} of direction {} does not lie inside patch {}", t, d, c.patch));
        merged[size_t(c.patch)].at[size_t(d)].push_back(t);
      }
  }
  std::vector<std::vector<PatchPiece>> pieces(static_cast<size_t>(n));
  std::vector<NurbsPatch> appended;
  for (int k = 0; k < n; ++k) {
    PatchCuts& c = merged[size_t(k)];
    for (auto& at : c.at) {
      std::sort(at.begin(), at.end());
      at.erase(std::unique(at.begin(), at.end()), at.end());
    }
    auto cut = pieces_of(patches[size_t(k)], c);
    for (size_t i = 0; i < cut.size(); ++i) {
      PatchPiece piece = cut[i].second;
      if (i == 0) {
        piece.patch = k;
        patches[size_t(k)] = std::move(cut[i].first);
      } else {
        piece.patch = n + int(appended.size());
        appended.push_back(std::move(cut[i].first));
      }
      pieces[size_t(k)].push_back(piece);
    }
  }
  for (auto& p : appended) patches.push_back(std::move(p));

  // Tolerance: 1e-9 of the body's size (as the body joins sides).
  Eigen::VectorXd lo = patches[0].points().colwise().minCoeff(), hi = patches[0].points().colwise().maxCoeff();
  for (const NurbsPatch& p : patches) {
    lo = lo.cwiseMin(p.points().colwise().minCoeff().transpose());
    hi = hi.cwiseMax(p.points().colwise().maxCoeff().transpose());
  }
  const double tol = 1e-9 * (hi - lo).norm();
  const int pd = patches[0].param_dim();

  std::vector<PatchInterface> joined;
  for (const PatchInterface& itf : interfaces) {
    const auto first = piece_sides(pieces[size_t(itf.first.patch)], pd, itf.first.face);
    const auto second = piece_sides(pieces[size_t(itf.second.patch)], pd, itf.second.face);
    for (const PatchSide& a : first) {
      const auto match = std::find_if(second.begin(), second.end(), [&](const PatchSide& b) {
        return !(a == b) && same_corners(patches[size_t(a.patch)], a.face, patches[size_t(b.patch)], b.face, tol);
      });
      if (match == second.end() || first.size() != second.size())
        throw std::invalid_argument(fmt::format(
            "the cut leaves patch {} side {} joined to only part of patch {} side {}: cut both patches at the same place",
            itf.first.patch, gismo_side_name(gismo_side_of(itf.first.face)), itf.second.patch,
            gismo_side_name(gismo_side_of(itf.second.face))));
      // A seam (a patch joined to itself) meets every pair twice: keep one.
      const PatchInterface pair{a, *match}, mirrored{*match, a};
      if (std::none_of(joined.begin(), joined.end(), [&](const PatchInterface& j) {
            return (j.first == pair.first && j.second == pair.second) ||
                   (j.first == mirrored.first && j.second == mirrored.second);
          }))
        joined.push_back(pair);
    }
  }
  // Pieces of one patch meet where a cut passed between them.
  for (const auto& cut : pieces)
    for (const PatchPiece& a : cut)
      for (const PatchPiece& b : cut)
        for (int d = 0; d < pd; ++d) {
          bool neighbours = a.box[size_t(d)][1] == b.box[size_t(d)][0];
          for (int e = 0; e < pd; ++e)
            if (e != d) neighbours = neighbours && a.box[size_t(e)] == b.box[size_t(e)];
          if (neighbours) joined.push_back({PatchSide{a.patch, Face{d, true}}, PatchSide{b.patch, Face{d, false}}});
        }
  interfaces = std::move(joined);
  return pieces;
}

}  // namespace igac
