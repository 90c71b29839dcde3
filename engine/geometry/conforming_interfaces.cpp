// SPDX-License-Identifier: BSD-3-Clause
#include "engine/geometry/conforming_interfaces.hpp"

#include <map>
#include <optional>

#include "engine/geometry/topology.hpp"
#include "engine/spline/refinement.hpp"

namespace igac {

namespace {

// Which of b's directions runs along direction `da` of a's side, and whether
// it runs the other way: found from the sides' corners.
std::optional<std::pair<int, bool>> partner_direction(const NurbsPatch& a, const Face& fa, int k, const NurbsPatch& b,
                                                      const Face& fb, double tol) {
  const int n = a.param_dim() - 1;
  std::vector<int> start(n, 0), step(n, 0);
  step[k] = 1;
  auto find = [&](const Eigen::VectorXd& x) -> std::optional<std::vector<int>> {
    for (int c = 0; c < (1 << n); ++c) {
      std::vector<int> bits(n);
      for (int i = 0; i < n; ++i) bits[i] = (c >> i) & 1;
      if ((face_corner(b, fb, bits) - x).norm() <= tol) return bits;
    }
    return std::nullopt;
  };
  const auto b0 = find(face_corner(a, fa, start)), b1 = find(face_corner(a, fa, step));
  if (!b0 || !b1) return std::nullopt;
  const std::vector<int> dirs = face_directions(b.param_dim(), fb);
  for (int i = 0; i < n; ++i)
    if ((*b0)[i] != (*b1)[i]) return std::pair{dirs[i], (*b0)[i] == 1};
  return std::nullopt;
}

KnotVector reflected(const KnotVector& kv) {
  std::vector<double> k(kv.knots().rbegin(), kv.knots().rend());
  const double s = kv.first() + kv.last();
  for (double& t : k) t = s - t;
  for (int i = 0; i <= kv.degree(); ++i)  // the ends exactly
    k[i] = kv.first(), k[k.size() - 1 - i] = kv.last();
  return KnotVector(kv.degree(), std::move(k));
}

}  // namespace

std::vector<InsertedKnots> make_interfaces_conform(std::vector<NurbsPatch>& patches,
                                                   const std::vector<PatchInterface>& interfaces) {
  std::map<std::pair<int, int>, int> inserted;
  if (patches.empty()) return {};
  const double tol = coincidence_tolerance(patches);
  const int rounds = int(patches.size()) * patches[0].param_dim() + 1;
  for (int round = 0; round < rounds; ++round) {
    bool changed = false;
    for (const PatchInterface& itf : interfaces) {
      NurbsPatch &a = patches[itf.first.patch], &b = patches[itf.second.patch];
      const std::vector<int> dirs = face_directions(a.param_dim(), itf.first.face);
      for (int k = 0; k < int(dirs.size()); ++k) {
        const auto partner = partner_direction(a, itf.first.face, k, b, itf.second.face, tol);
        if (!partner) continue;  // sides that do not meet: the body says so
        const int da = dirs[k], db = partner->first;
        const bool reverse = partner->second;
        const KnotVector &ka = a.knots(da), &kb = b.knots(db);
        if (ka.degree() != kb.degree()) continue;  // the body refuses it
        const KnotVector for_a = (reverse ? reflected(kb) : kb).united_with(ka);
        const KnotVector for_b = (reverse ? reflected(for_a) : for_a).united_with(kb);
        for (auto [p, d, kv] : {std::tuple{itf.first.patch, da, &for_a}, std::tuple{itf.second.patch, db, &for_b}}) {
          const int added = kv->size() - patches[p].knots(d).size();
          if (added <= 0) continue;
          patches[p] = refine_to(patches[p], d, *kv);
          inserted[{p, d}] += added;
          changed = true;
        }
      }
    }
    if (!changed) break;
  }
  std::vector<InsertedKnots> out;
  for (const auto& [pd, count] : inserted) out.push_back({pd.first, pd.second, count});
  return out;
}

}  // namespace igac
