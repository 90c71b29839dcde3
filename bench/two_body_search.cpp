// SPDX-License-Identifier: BSD-3-Clause
// bench/two_body_search: a whole two-body contact solve on a large master
// face (issue 22: "Search that scales ... measure it on a 3D pair with 10k+
// master elements"), and what the master search cost inside it: the
// closest-point queries (MasterSurface::project: the bounding-box tree, then
// Newton on each candidate element; those of the slave quadrature points
// and those that cut the slave elements, segmented integration), counted
// and timed by the master surface itself during the run; the peak memory
// of the process.  Small deformation only: a large-deformation problem
// searches on its own copies of the master surfaces, which are not counted
// here (it refuses such a case; bench/newton_vs_linear times those).
//
//   build/bench/two_body_search CASE.toml [--integration segmented|element] [--csv FILE]
//
// One row per run (one run per process, so that the peak memory is the run's).
#include <sys/resource.h>

#include <fmt/format.h>
#include <fstream>
#include <omp.h>
#include <string>

#include "engine/stopwatch.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

using namespace igac;

int main(int argc, char** argv) {
  if (argc < 2) {
    fmt::print(stderr, "usage: {} CASE.toml [--integration segmented|element] [--csv FILE]\n", argv[0]);
    return 2;
  }
  omp_set_dynamic(0);  // as igac: each region takes the free cores (engine/free_cores.hpp)
  std::string csv_path, integration;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--csv" && i + 1 < argc) csv_path = argv[++i];
    else if (a == "--integration" && i + 1 < argc) integration = argv[++i];
    else {
      fmt::print(stderr, "unknown argument '{}'\n", a);
      return 2;
    }
  }
  Stopwatch clock;
  CaseSpec spec = read_case(argv[1]);
  if (spec.finite_strain()) {  // (its problem searches on its own copies of the master surfaces: none counted here)
    fmt::print(stderr, "{}: a large-deformation case; this bench counts the searches of small-deformation runs "
                       "(for large deformation: build/bench/newton_vs_linear)\n", argv[1]);
    return 2;
  }
  if (!integration.empty())
    for (ContactSpec& c : spec.contacts) {
      const auto i = mortar_integration_named(integration);
      if (!i) {
        fmt::print(stderr, "--integration: \"{}\" is not one of \"segmented\", \"element\"\n", integration);
        return 2;
      }
      c.integration = *i;
    }
  Model m = build_model(spec);
  const double setup_s = clock.seconds();
  for (const auto& c : m.contacts)  // (the setup's own queries: the checks of the pair)
    if (c.master) c.master->reset_counters();
  clock.restart();
  const RunResult r = solve_model(m, quiet_run());
  const double solve_s = clock.seconds();
  int master_elements = 0;
  MasterSurface::SearchCounters search;
  for (const auto& c : m.contacts)
    if (c.master) {
      master_elements += c.master->num_elements();
      const MasterSurface::SearchCounters s = c.master->counters();
      search.queries += s.queries;
      search.candidates += s.candidates;
      search.seconds += s.seconds;
    }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double peak_mib = double(usage.ru_maxrss) / 1024.0;
  const int iterations = r.contact ? int(r.contact->solution.active_set_sizes.size()) : 0;
  const double force = r.reactions.empty() ? 0.0 : r.reactions.front().normal_force;
  const std::string header =
      "case,integration,master_elements,dofs,multipliers,status,active_set_iterations,contact_force,applied_force,"
      "setup_s,solve_s,search_s,search_share_of_solve,queries,candidates_per_query,peak_rss_mib\n";
  const std::string row = fmt::format(
      "{},{},{},{},{},{},{},{:.8g},{:.8g},{:.3f},{:.3f},{:.3f},{:.4f},{},{:.3f},{:.0f}\n", spec.name,
      spec.contacts.empty() ? "" : name_of(spec.contacts.front().integration), master_elements, m.dofs->num_free(),
      r.contact ? int(r.contact->solution.lambda.size()) : 0, r.status, iterations, force, r.applied_force, setup_s,
      solve_s, search.seconds, search.seconds / solve_s, search.queries,
      search.queries ? double(search.candidates) / double(search.queries) : 0.0, peak_mib);
  fmt::print("{}{}", header, row);
  if (!csv_path.empty()) {
    std::ofstream out(csv_path);
    out << header << row;
  }
  return r.status == "converged" ? 0 : 1;
}
