// SPDX-License-Identifier: BSD-3-Clause
#include "engine/geometry/topology.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace igac {

namespace {

constexpr int kSamples = 5;  // per direction of a side; odd, so the middle maps to itself

// A side's points at the kSamples^(pd - 1) grid of its parameters, first
// direction fastest.
struct SampledSide {
  PatchSide side;
  int dirs = 0;  // tangential directions: 1 (a 2D body) or 2 (3D)
  std::vector<Eigen::VectorXd> x;
  const Eigen::VectorXd& at(int i, int j) const { return x[i + kSamples * j]; }
  Eigen::VectorXd corner_mean;  // the same for every orientation: the key of the search
};

SampledSide sample(const NurbsPatch& patch, const PatchSide& s) {
  const NurbsPatch face = patch.face_patch(s.face);
  SampledSide out{s, face.param_dim(), {}, {}};
  const int nj = out.dirs == 2 ? kSamples : 1;
  Eigen::VectorXd xi(out.dirs);
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < kSamples; ++i) {
      for (int d = 0; d < out.dirs; ++d) {
        const KnotVector& kv = face.knots(d);
        const double a = kv.knots().front(), b = kv.knots().back();
        xi[d] = a + (b - a) * double(d == 0 ? i : j) / (kSamples - 1);
      }
      out.x.push_back(face.point(xi));
    }
  const int last = kSamples - 1;
  out.corner_mean = out.dirs == 1 ? Eigen::VectorXd((out.at(0, 0) + out.at(last, 0)) / 2)
                                  : Eigen::VectorXd((out.at(0, 0) + out.at(last, 0) + out.at(0, last) + out.at(last, last)) / 4);
  return out;
}

// Length (2D body) or area (3D body) of the side, from its samples.
double measure(const SampledSide& s) {
  double m = 0;
  if (s.dirs == 1) {
    for (int i = 0; i + 1 < kSamples; ++i) m += (s.at(i + 1, 0) - s.at(i, 0)).norm();
    return m;
  }
  auto area = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& c) {
    const Eigen::Vector3d u = (b - a).head<3>(), v = (c - a).head<3>();
    return 0.5 * u.cross(v).norm();
  };
  for (int j = 0; j + 1 < kSamples; ++j)
    for (int i = 0; i + 1 < kSamples; ++i)
      m += area(s.at(i, j), s.at(i + 1, j), s.at(i, j + 1)) + area(s.at(i + 1, j + 1), s.at(i, j + 1), s.at(i + 1, j));
  return m;
}

enum class Match { none, corners_only, all };

// Does `b` coincide with `a` under some orientation?
Match compare(const SampledSide& a, const SampledSide& b, double tol) {
  const int nj = a.dirs == 2 ? kSamples : 1;
  Match best = Match::none;
  for (int o = 0; o < (a.dirs == 2 ? 8 : 2); ++o) {
    const bool flip0 = o & 1, flip1 = o & 2, swap = o & 4;
    auto partner = [&](int i, int j) -> const Eigen::VectorXd& {
      int p = swap ? j : i, q = swap ? i : j;
      if (flip0) p = kSamples - 1 - p;
      if (flip1 && a.dirs == 2) q = kSamples - 1 - q;
      return b.at(p, q);
    };
    bool corners = true, all = true;
    for (int j = 0; j < nj && corners; ++j)
      for (int i = 0; i < kSamples; ++i) {
        const bool corner = (i == 0 || i == kSamples - 1) && (nj == 1 || j == 0 || j == kSamples - 1);
        if ((a.at(i, j) - partner(i, j)).norm() <= tol) continue;
        all = false;
        if (corner) {
          corners = false;
          break;
        }
      }
    if (corners && all) return Match::all;
    if (corners) best = Match::corners_only;
  }
  return best;
}

}  // namespace

double coincidence_tolerance(const std::vector<NurbsPatch>& patches) {
  if (patches.empty()) return 0;
  Eigen::VectorXd lo = patches[0].points().colwise().minCoeff(), hi = patches[0].points().colwise().maxCoeff();
  for (const auto& p : patches) {
    lo = lo.cwiseMin(p.points().colwise().minCoeff().transpose());
    hi = hi.cwiseMax(p.points().colwise().maxCoeff().transpose());
  }
  return 1e-9 * std::max((hi - lo).norm(), 1e-300);
}

CoincidentSides find_coincident_sides(const std::vector<NurbsPatch>& patches, const std::vector<PatchSide>& candidates) {
  CoincidentSides out;
  if (patches.empty()) return out;
  const double tol = coincidence_tolerance(patches);
  const double extent = 1e9 * tol;
  std::vector<SampledSide> sides;
  for (const PatchSide& s : candidates) {
    SampledSide ss = sample(patches[s.patch], s);
    // A side collapsed to a point or (3D) a curve has nothing to share.
    const double scale = ss.dirs == 1 ? extent : extent * extent;
    if (measure(ss) > 1e-6 * scale) sides.push_back(std::move(ss));
  }
  // Sides that share their corners have the same mean of corners, whatever
  // the orientation: compare only sides whose means are close in x.
  std::sort(sides.begin(), sides.end(),
            [](const SampledSide& a, const SampledSide& b) { return a.corner_mean[0] < b.corner_mean[0]; });
  std::vector<bool> used(sides.size(), false);
  for (size_t a = 0; a < sides.size(); ++a) {
    if (used[a]) continue;
    for (size_t b = a + 1; b < sides.size() && sides[b].corner_mean[0] - sides[a].corner_mean[0] <= tol; ++b) {
      if (used[b] || (sides[b].corner_mean - sides[a].corner_mean).norm() > tol) continue;
      const Match m = compare(sides[a], sides[b], tol);
      if (m == Match::none) continue;
      PatchInterface pair{sides[a].side, sides[b].side};
      if (pair.second.patch < pair.first.patch ||
          (pair.second.patch == pair.first.patch && gismo_side_of(pair.second.face) < gismo_side_of(pair.first.face)))
        std::swap(pair.first, pair.second);
      if (m == Match::corners_only) {
        out.corners_only.push_back(pair);
        continue;
      }
      out.coincide.push_back(pair);
      used[a] = used[b] = true;
      break;
    }
  }
  // A side joined to one side and sharing corners with another is joined.
  auto joined = [&](const PatchSide& s) {
    for (const PatchInterface& i : out.coincide)
      if (i.first == s || i.second == s) return true;
    return false;
  };
  std::erase_if(out.corners_only, [&](const PatchInterface& i) { return joined(i.first) || joined(i.second); });
  auto order = [](const PatchInterface& x, const PatchInterface& y) {
    auto key = [](const PatchInterface& i) {
      return std::array<int, 4>{i.first.patch, gismo_side_of(i.first.face), i.second.patch, gismo_side_of(i.second.face)};
    };
    return key(x) < key(y);
  };
  std::sort(out.coincide.begin(), out.coincide.end(), order);
  std::sort(out.corners_only.begin(), out.corners_only.end(), order);
  return out;
}

}  // namespace igac
