// SPDX-License-Identifier: BSD-3-Clause
#include "engine/body.hpp"

#include <algorithm>
#include <cmath>
#include <array>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <map>
#include <numeric>

#include "engine/geometry/topology.hpp"

namespace igac {

namespace {

int largest_degree(const NurbsPatch& p) {
  int d = 0;
  for (int k = 0; k < p.param_dim(); ++k) d = std::max(d, p.degree(k));
  return d;
}

// Breakpoints of a direction mapped to [0, 1].
std::vector<double> unit_breakpoints(const KnotVector& kv) {
  std::vector<double> b = kv.breakpoints();
  const double a = b.front(), len = b.back() - b.front();
  for (double& x : b) x = (x - a) / len;
  return b;
}

bool same_breaks(const std::vector<double>& a, std::vector<double> b, bool reversed) {
  if (a.size() != b.size()) return false;
  if (reversed) {
    std::reverse(b.begin(), b.end());
    for (double& x : b) x = 1 - x;
  }
  for (size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > 1e-10) return false;
  return true;
}

// Do the two sides have the same breakpoints in some pairing of their
// directions (up to reversal)?
bool sides_have_same_knots(const NurbsPatch& fa, const NurbsPatch& fb) {
  const int n = fa.param_dim();
  if (fb.param_dim() != n) return false;
  std::vector<int> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  do {
    bool ok = true;
    for (int d = 0; d < n && ok; ++d) {
      const auto a = unit_breakpoints(fa.knots(d)), b = unit_breakpoints(fb.knots(perm[d]));
      ok = fa.degree(d) == fb.degree(perm[d]) && (same_breaks(a, b, false) || same_breaks(a, b, true));
    }
    if (ok) return true;
  } while (std::next_permutation(perm.begin(), perm.end()));
  return false;
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the smaller (earlier patch) represents
  }
};

std::string side_name(int patch, const Face& f) {
  return fmt::format("patch {} ({})", patch, gismo_side_name(gismo_side_of(f)));
}

}  // namespace

Body::Body(NurbsPatch patch) {
  patches_.push_back(std::move(patch));
  num_cps_ = patches_[0].num_control_points();
  body_cps_.emplace_back(num_cps_);
  std::iota(body_cps_[0].begin(), body_cps_[0].end(), 0);
  points_ = patches_[0].points();
  degree_ = largest_degree(patches_[0]);
}

Body::Body(std::vector<NurbsPatch> patches, const std::vector<PatchInterface>& interfaces)
    : patches_(std::move(patches)), interfaces_(interfaces) {
  if (patches_.empty()) throw BodyError("a body needs at least one patch");
  const int sd = patches_[0].space_dim(), pd = patches_[0].param_dim();
  // Patches of different degrees may form a body as long as no interface
  // joins two of them (two bodies of a case, each of its own degree): the
  // interface check below compares the sides' degrees.
  degree_ = 0;
  for (const NurbsPatch& p : patches_) degree_ = std::max(degree_, largest_degree(p));
  std::vector<int> offset{0};
  for (size_t k = 0; k < patches_.size(); ++k) {
    const NurbsPatch& p = patches_[k];
    if (p.space_dim() != sd || p.param_dim() != pd)
      throw BodyError(fmt::format("patch {} has {} parametric directions in {}D, patch 0 {} in {}D", k, p.param_dim(),
                                  p.space_dim(), pd, sd));
    offset.push_back(offset.back() + p.num_control_points());
  }
  const double tol = coincidence_tolerance(patches_);

  UnionFind uf(offset.back());
  for (const PatchInterface& itf : interfaces_) {
    const PatchSide& a = itf.first;
    const PatchSide& b = itf.second;
    for (const PatchSide& s : {a, b})
      if (s.patch < 0 || s.patch >= num_patches() || s.face.direction >= pd)
        throw BodyError(fmt::format("an interface names {} of a body of {} patches in {}D", side_name(s.patch, s.face),
                                    num_patches(), pd));
    const NurbsPatch &pa = patches_[a.patch], &pb = patches_[b.patch];
    const std::string where = fmt::format("interface {} - {}", side_name(a.patch, a.face), side_name(b.patch, b.face));
    const NurbsPatch fa = pa.face_patch(a.face), fb = pb.face_patch(b.face);
    const std::vector<int> ca = pa.face_control_points(a.face), cb = pb.face_control_points(b.face);
    if (ca.size() != cb.size() || !sides_have_same_knots(fa, fb))
      throw BodyError(fmt::format("{} is not conforming: the sides have different knots ({} and {} control points); "
                                  "refine both patches alike along the interface (a body built from a case has the missing "
                                  "knots inserted first, engine/geometry/conforming_interfaces.hpp: there, the sides "
                                  "run at different speeds along the interface or differ in degree)",
                                  where, ca.size(), cb.size()));
    // Match b's control points to a's through a grid of cells of size `cell`.
    const double cell = 1e3 * tol;
    auto key = [&](const Eigen::VectorXd& x) {
      std::array<long long, 3> k{0, 0, 0};
      for (int d = 0; d < sd; ++d) k[d] = (long long)std::floor(x[d] / cell);
      return k;
    };
    std::map<std::array<long long, 3>, std::vector<int>> grid;
    for (size_t j = 0; j < cb.size(); ++j) grid[key(pb.points().row(cb[j]).transpose())].push_back(int(j));
    double ratio = 0;
    for (size_t i = 0; i < ca.size(); ++i) {
      const Eigen::VectorXd x = pa.points().row(ca[i]).transpose();
      const auto k0 = key(x);
      int found = -1;
      const int n_nb = sd == 2 ? 9 : 27;
      for (int nb = 0; nb < n_nb && found < 0; ++nb) {
        std::array<long long, 3> k = k0;
        for (int d = 0, r = nb; d < sd; ++d, r /= 3) k[d] += r % 3 - 1;
        if (auto it = grid.find(k); it != grid.end())
          for (int j : it->second)
            if ((pb.points().row(cb[j]).transpose() - x).norm() <= tol) found = j;
      }
      if (found < 0)
        throw BodyError(fmt::format("{} is not conforming: control point ({:.6g}) of the first side has no partner on "
                                    "the second (do the sides meet, with the same knots?)",
                                    where, fmt::join(x, ", ")));
      const double r = pa.weights()[ca[i]] / pb.weights()[cb[found]];
      if (i == 0) ratio = r;
      else if (std::abs(r - ratio) > 1e-10 * ratio)
        throw BodyError(fmt::format("{} is not conforming: the weights of the two sides differ at ({:.6g})", where,
                                    fmt::join(x, ", ")));
      uf.join(offset[a.patch] + ca[i], offset[b.patch] + cb[found]);
    }
  }
  // Number the representatives in order: patch 0's control points first.
  std::vector<int> number(offset.back(), -1);
  body_cps_.resize(patches_.size());
  for (size_t k = 0; k < patches_.size(); ++k) {
    body_cps_[k].resize(patches_[k].num_control_points());
    for (int i = 0; i < patches_[k].num_control_points(); ++i) {
      const int r = uf.find(offset[k] + i);
      if (number[r] < 0) number[r] = num_cps_++;
      body_cps_[k][i] = number[r];
    }
  }
  points_.resize(num_cps_, sd);
  for (size_t k = 0; k < patches_.size(); ++k)
    for (int i = 0; i < patches_[k].num_control_points(); ++i) points_.row(body_cps_[k][i]) = patches_[k].points().row(i);
}

int Body::num_elements() const {
  int n = 0;
  for (const auto& p : patches_) n += p.num_elements();
  return n;
}

std::vector<int> Body::side_control_points(const PatchSide& s) const {
  if (s.patch < 0 || s.patch >= num_patches() || s.face.direction < 0 || s.face.direction >= param_dim())
    throw BodyError(fmt::format("no side {} on a body of {} patches", side_name(s.patch, s.face), num_patches()));
  std::vector<int> cps = patches_[s.patch].face_control_points(s.face);
  for (int& c : cps) c = body_cps_[s.patch][c];
  return cps;
}

NurbsPatch Body::side_patch(const PatchSide& s) const { return patches_[s.patch].face_patch(s.face); }

PatchQuadrature Body::side_quadrature(const PatchSide& s, int points) const {
  return PatchQuadrature(side_patch(s), points, s.face, side_control_points(s));
}

Eigen::MatrixXd Body::patch_field(int k, const Eigen::MatrixXd& body_field) const {
  Eigen::MatrixXd out(patches_[k].num_control_points(), body_field.cols());
  for (int i = 0; i < out.rows(); ++i) out.row(i) = body_field.row(body_cps_[k][i]);
  return out;
}

std::string Body::describe(const PatchSide& s) const { return side_name(s.patch, s.face); }

std::vector<int> Body::parts() const {
  // Labels spread along the interfaces until nothing changes (a few sweeps
  // for the handful of patches a body has).
  std::vector<int> part(patches_.size());
  for (size_t k = 0; k < part.size(); ++k) part[k] = int(k);
  for (bool changed = true; changed;) {
    changed = false;
    for (const PatchInterface& itf : interfaces_) {
      int& a = part[itf.first.patch];
      int& b = part[itf.second.patch];
      if (a != b) {
        a = b = std::min(a, b);
        changed = true;
      }
    }
  }
  return part;
}

BodyQuadrature::BodyQuadrature(const Body& body, int points) {
  for (int k = 0; k < body.num_patches(); ++k) {
    patches_.emplace_back(body.patch(k), points, std::nullopt,
                          body.numbered_as_patch() ? std::vector<int>{} : body.body_cps(k));
    first_.push_back(first_.back() + patches_.back().num_elements());
    num_local_ = std::max(num_local_, patches_.back().num_local());
  }
}

int BodyQuadrature::patch_of(int e) const {
  return int(std::upper_bound(first_.begin(), first_.end(), e) - first_.begin()) - 1;
}

void BodyQuadrature::evaluate(int e, ElementData& out, bool gradients) const {
  const int k = patches_.size() == 1 ? 0 : patch_of(e);
  patches_[k].evaluate(e - first_[k], out, gradients);
}

void BodyQuadrature::control_points(int e, std::vector<int>& cps) const {
  const int k = patches_.size() == 1 ? 0 : patch_of(e);
  patches_[k].control_points(e - first_[k], cps);
}

}  // namespace igac
