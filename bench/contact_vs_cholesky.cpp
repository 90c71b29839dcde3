// SPDX-License-Identifier: BSD-3-Clause
// bench/contact_vs_cholesky: the cost of the whole small-deformation contact
// solve against the floor of any direct method, one sparse Cholesky
// factorisation (analysis + numeric, CHOLMOD's own ordering) of the same
// stiffness matrix with the rigid mode pinned, both measured in this process.
//
//   build/bench/contact_vs_cholesky CASE.toml REFINE [REFINE ...] [--csv FILE] [--repeat N]
//                                   [--free-ordering]
//
// Writes one CSV row per refinement: dofs, multipliers, active set
// iterations, the best of N timings of each, their ratio, the contact
// solve's own split (factorisation, Schur complement, the rest), whether the
// face was ordered last, the columns of L^-1 P G^T it computed, the rows of
// the face's reach in the factor, the BLAS library.
#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <fstream>
#include <omp.h>
#include <string>

#include "engine/stopwatch.hpp"
#include "contact/small_strain_contact.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

using namespace igac;

static std::string blas_library() {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line))
    if (line.find("blas") != std::string::npos) return line.substr(line.find('/'));
  return "unknown";
}

int main(int argc, char** argv) {
  if (argc < 3) {
    fmt::print(stderr, "usage: {} CASE.toml REFINE [REFINE ...] [--csv FILE] [--repeat N]\n", argv[0]);
    return 2;
  }
  omp_set_dynamic(0);  // as igac: each region takes the free cores (engine/free_cores.hpp)
  std::string csv_path;
  int repeat = 3;
  bool face_last = true;
  std::vector<int> refines;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--csv" && i + 1 < argc) csv_path = argv[++i];
    else if (a == "--repeat" && i + 1 < argc) repeat = std::stoi(argv[++i]);
    else if (a == "--free-ordering") face_last = false;
    else refines.push_back(std::stoi(a));
  }
  std::string csv =
      "case,refine,dofs,multipliers,active_set_iterations,cholesky_s,contact_solve_s,ratio,"
      "contact_factorize_s,contact_schur_s,contact_iterations_s,face_last,schur_columns,reach_rows,blas\n";
  fmt::print("{}", csv);  // the header first: stdout is the same CSV as --csv FILE
  for (int refine : refines) {
    CaseSpec spec = read_case(argv[1]);
    apply_overrides(spec, {}, refine);
    const Model m = build_model(spec);
    const Body& body = m.body;
    LinearSystem sys = assemble_linear_elasticity(body, *m.dofs, m.material, Eigen::VectorXd::Zero(body.space_dim()));
    for (const auto& p : spec.pressure) {
      std::vector<PatchSide> faces;
      for (const auto& n : p.faces) {
        const auto f = *find_faces(m, n);
        faces.insert(faces.end(), f.begin(), f.end());
      }
      add_pressure_load(body, *m.dofs, faces, p.value, sys.f);
    }
    const RigidModes modes = free_rigid_modes(body, *m.dofs);
    const WeightedGapOperator op = assemble_contact_operator(m);
    const Eigen::SparseMatrix<double> Kp = pin_equations(sys.K, modes.pinned);
    ContactSolverOptions opt;
    opt.complementarity_scale = spec.E / m.mesh_size;
    opt.face_last = face_last;
    double best_chol = 1e300, best_contact = 1e300;
    int iterations = 0;
    ContactSolution best;
    for (int r = 0; r < repeat; ++r) {
      {
        SparseCholesky chol;
        const Stopwatch t0;
        chol.analyze(Kp);
        chol.factorize(Kp);
        best_chol = std::min(best_chol, t0.seconds());
      }
      {
        SparseCholesky chol;
        const Stopwatch t0;
        ContactSolution s = solve_small_strain_contact(sys.K, sys.f, op, modes, chol, opt);
        const double dt = t0.seconds();
        if (dt < best_contact) best = std::move(s);
        best_contact = std::min(best_contact, dt);
        iterations = int(best.active_set_sizes.size());
        if (!best.converged) fmt::print(stderr, "warning: refine {}: {}\n", refine, best.status);
      }
    }
    const std::string row = fmt::format(
        "{},{},{},{},{},{:.4f},{:.4f},{:.3f},{:.4f},{:.4f},{:.4f},{},{},{},{}\n", spec.name, refine, m.dofs->num_free(),
        m.num_multipliers(), iterations, best_chol, best_contact, best_contact / best_chol, best.factorize_s, best.schur_s,
        best.iterations_s, face_last ? 1 : 0, best.schur_columns,
        best.reach_rows, blas_library());
    fmt::print("{}", row);
    csv += row;
  }
  if (!csv_path.empty()) std::ofstream(csv_path) << csv;
  return 0;
}
