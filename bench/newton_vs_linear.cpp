// SPDX-License-Identifier: BSD-3-Clause
// bench/newton_vs_linear: the cost of one Newton iteration of the
// large-deformation path against one small-deformation solve of the same
// mesh (linear-elastic assembly + one CHOLMOD analysis and factorisation of
// the stiffness with the rigid motions pinned), both measured in this
// process.  The target: a Newton iteration within 1.5 x (2D) and
// 2 x (3D) of that.
//
//   build/bench/newton_vs_linear CASE.toml [REFINE ...] [--csv FILE] [--repeat N]
//
// One CSV row per refinement: dofs, multipliers, load steps, Newton
// iterations, cut-backs, the Newton time and its split (residuals,
// Jacobians, factorisations, Schur complements, solves incl. GMRES), GMRES
// iterations and LU fallbacks, the best of N small-deformation solves
// (assembly, factorisation), and the ratio per Newton iteration.
#include <algorithm>
#include <fmt/format.h>
#include <fstream>
#include <omp.h>
#include <string>

#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "engine/cholesky.hpp"
#include "engine/linear_static.hpp"
#include "engine/stopwatch.hpp"

using namespace igac;

int main(int argc, char** argv) {
  if (argc < 2) {
    fmt::print(stderr, "usage: {} CASE.toml [REFINE ...] [--csv FILE] [--repeat N]\n", argv[0]);
    return 2;
  }
  omp_set_dynamic(0);  // as igac: each region takes the free cores (engine/free_cores.hpp)
  std::string csv_path;
  int repeat = 3;
  std::vector<int> refines;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--csv" && i + 1 < argc) csv_path = argv[++i];
    else if (a == "--repeat" && i + 1 < argc) repeat = std::stoi(argv[++i]);
    else refines.push_back(std::stoi(a));
  }
  if (refines.empty()) refines.push_back(0);
  std::string csv =
      "case,refine,dofs,multipliers,status,load_steps,newton_iterations,cut_backs,newton_s,residual_s,jacobian_s,"
      "factorize_s,schur_s,solve_s,gmres_iterations,lu_fallbacks,shifted_factors,linear_assembly_s,linear_factorize_s,"
      "newton_iteration_s,ratio\n";
  fmt::print("{}", csv);  // the header first: stdout is the same CSV as --csv FILE
  for (int refine : refines) {
    CaseSpec spec = read_case(argv[1]);
    apply_overrides(spec, {}, refine);
    Model m = build_model(spec);
    const RunResult r = solve_model(m, quiet_run());
    const LoadSteppingSummary& s = *r.load_steps;
    int iterations = 0, cut_backs = 0;
    for (const auto& st : s.steps) {
      iterations += st.newton_iterations;
      cut_backs += st.cut_backs;
    }
    // the small-deformation solve of the same mesh
    const Body& patch = m.body;
    double best_assembly = 1e300, best_factor = 1e300;
    for (int k = 0; k < repeat; ++k) {
      Stopwatch clock;
      const LinearSystem sys = assemble_linear_elasticity(patch, *m.dofs, m.material, Eigen::VectorXd::Zero(patch.space_dim()));
      best_assembly = std::min(best_assembly, clock.seconds());
      const RigidModes modes = free_rigid_modes(patch, *m.dofs);
      const Eigen::SparseMatrix<double> Kp = pin_equations(sys.K, modes.pinned);
      SparseCholesky chol;
      clock.restart();
      chol.analyze(Kp);
      chol.factorize(Kp);
      best_factor = std::min(best_factor, clock.seconds());
    }
    // per Newton iteration: every Jacobian set up (incl. the predictor's)
    const double per_iteration = s.newton_seconds / std::max(s.linear.setups, 1);
    const std::string row = fmt::format(
        "{},{},{},{},\"{}\",{},{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{},{},{},{:.4f},{:.4f},{:.4f},{:.3f}\n",
        spec.name, refine, m.dofs->num_free(), m.num_multipliers(), r.status, s.steps.size(), iterations, cut_backs,
        s.newton_seconds, s.residual_seconds, s.jacobian_seconds, s.linear.factorize_s, s.linear.schur_s, s.linear.solve_s,
        s.linear.krylov_iterations, s.linear.fallbacks, s.linear.shifted, best_assembly, best_factor, per_iteration,
        per_iteration / (best_assembly + best_factor));
    fmt::print("{}", row);
    csv += row;
  }
  if (!csv_path.empty()) std::ofstream(csv_path) << csv;
  return 0;
}
