// SPDX-License-Identifier: BSD-3-Clause
// bench/master_search: the closest-point search of two-body contact
// (contact/master_surface.hpp) on a sphere octant's curved face of N x N
// degree-3 master elements: per query near the surface, the time and the
// elements Newton ran on, by the tree and (up to --brute-max elements) by
// trying every element, measured in one process.
//
// The queries lie between radii LO and HI (default 0.99 and 1.01: near the
// surface; points far from it, as a body's far side asks, are the harder).
//
//   build/bench/master_search N [N ...] [--queries Q] [--radius LO HI] [--brute-max M] [--csv FILE]
#include <chrono>
#include <fmt/format.h>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "contact/master_surface.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/spline/refinement.hpp"

using namespace igac;

int main(int argc, char** argv) {
  std::vector<int> sizes;
  int queries = 200, brute_max = 4096;
  std::string csv;
  double radius_lo = 0.99, radius_hi = 1.01;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--queries" && i + 1 < argc) queries = std::stoi(argv[++i]);
    else if (a == "--brute-max" && i + 1 < argc) brute_max = std::stoi(argv[++i]);
    else if (a == "--csv" && i + 1 < argc) csv = argv[++i];
    else if (a == "--radius" && i + 2 < argc) radius_lo = std::stod(argv[++i]), radius_hi = std::stod(argv[++i]);
    else sizes.push_back(std::stoi(a));
  }
  if (sizes.empty()) {
    fmt::print(stderr, "usage: {} N [N ...] [--queries Q] [--radius LO HI] [--brute-max M] [--csv FILE]\n", argv[0]);
    return 2;
  }
  const std::string header = "master_elements,queries,tree_s_per_query,tree_elements_per_query,brute_s_per_query,ratio\n";
  fmt::print("{}", header);
  std::string out = header;
  const Geometry g = sphere_octant(1.0);
  for (int n : sizes) {
    NurbsPatch patch = elevate_to(g.patch, 3);
    for (int d : {0, 2}) patch = refine_to(patch, d, KnotVector::uniform(3, n));
    const Body body(patch);
    const MasterSurface master(body, {g.faces.at("curved")[0]});
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> unit(0.05, 1.0), radius(radius_lo, radius_hi);
    std::vector<Eigen::VectorXd> points;
    for (int k = 0; k < queries; ++k)
      points.push_back(radius(rng) * Eigen::Vector3d(unit(rng), unit(rng), -unit(rng)).normalized());
    using clock = std::chrono::steady_clock;
    auto t0 = clock::now();
    long visited = 0;
    for (const auto& x : points) {
      int candidates = 0;
      master.project(x, &candidates);
      visited += candidates;
    }
    const double tree = std::chrono::duration<double>(clock::now() - t0).count() / queries;
    double brute = 0;
    if (master.num_elements() <= brute_max) {
      const int few = std::max(1, queries / 20);
      t0 = clock::now();
      for (int k = 0; k < few; ++k) master.project_by_every_element(points[k]);
      brute = std::chrono::duration<double>(clock::now() - t0).count() / few;
    }
    const std::string row = fmt::format("{},{},{:.3e},{:.1f},{},{}\n", master.num_elements(), queries, tree,
                                        double(visited) / queries, brute > 0 ? fmt::format("{:.3e}", brute) : "",
                                        brute > 0 ? fmt::format("{:.0f}", brute / tree) : "");
    fmt::print("{}", row);
    out += row;
  }
  if (!csv.empty()) std::ofstream(csv) << out;
  return 0;
}
