// SPDX-License-Identifier: BSD-3-Clause
#include "model/petsc_run.hpp"

#include <fmt/format.h>
#include <utility>

#ifdef IGAC_WITH_PETSC
#include <mpi.h>

#include "model/model.hpp"
#include "solvers/petsc_contact.hpp"
#include "solvers/petsc_newton.hpp"
#include "engine/prolongation.hpp"
#endif

namespace igac {

bool uses_petsc(const Model& m) { return m.spec.solver.petsc(); }

void take_report(const LinearBackend& backend, LinearSolverRecord& record) {
  const LinearBackendReport report = backend.report();
  record.type = report.type;
  record.method = report.method;
  record.iterations = report.iterations;
  record.ranks = report.ranks;
  record.peak_resident_all_ranks_gib = report.peak_resident_all_ranks_gib;
  if (const double kappa = backend.condition_estimate(); kappa > 0) record.condition_estimate = kappa;
}

#ifdef IGAC_WITH_PETSC
namespace {
// Rigid motions of the free equations (translations, rotations about the
// centroid), of each separate body apart (two bodies: 12 columns in 3D): the
// near null space that algebraic multigrid builds its coarse spaces from.
// Exact in the NURBS space (partition of unity).
Eigen::MatrixXd rigid_motions(const Model& m) {
  const Body& body = m.body;
  const DofMap& dofs = *m.dofs;
  // axisymmetric: the two translations (a rotation leaves the axis, and a
  // radial translation is only nearly free, as is the constant of any block)
  const bool revolved = body.patch(0).revolved();
  const int dim = body.space_dim(), n_modes = revolved ? 2 : dim == 2 ? 3 : 6;
  // the separate body of each control point, numbered 0, 1, ...
  const std::vector<int> part_of_patch = body.parts();
  std::vector<int> part_index(part_of_patch.size(), -1), part_of_point(body.num_control_points(), 0);
  int parts = 0;
  for (int k = 0; k < body.num_patches(); ++k) {
    int& index = part_index[part_of_patch[k]];
    if (index < 0) index = parts++;
    for (int cp : body.body_cps(k)) part_of_point[cp] = index;
  }
  std::vector<Eigen::RowVectorXd> centre(parts, Eigen::RowVectorXd::Zero(dim));
  std::vector<int> count(parts, 0);
  for (int p = 0; p < body.num_control_points(); ++p) {
    centre[part_of_point[p]] += body.points().row(p);
    ++count[part_of_point[p]];
  }
  for (int q = 0; q < parts; ++q) centre[q] /= std::max(count[q], 1);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(dofs.num_free(), n_modes * parts);
  for (int i = 0; i < dofs.num_dofs(); ++i) {
    const int eq = dofs.equation(i);
    if (eq < 0) continue;
    const int c = i % dim, q = part_of_point[i / dim], o = n_modes * q;
    const Eigen::RowVectorXd x = body.points().row(i / dim) - centre[q];
    M(eq, o + c) = 1.0;
    if (revolved) continue;
    if (dim == 2) {
      M(eq, o + 2) = c == 0 ? -x[1] : x[0];
    } else {  // rotations about x, y, z (each up to its sign)
      const int a = (c + 1) % 3, b = (c + 2) % 3;
      M(eq, o + 3 + b) = x[a];
      M(eq, o + 3 + a) = -x[b];
    }
  }
  return M;
}
// The prolongations of the spline multigrid, finest first: the case's mesh
// at --refine r from r - 1, ..., 1 from 0 (nested: each halves the spans of
// the one before).  The coarse models are built whole on every process
// (small next to the fine one: 1/8 of it, 1/64, ...).
std::vector<Eigen::SparseMatrix<double, Eigen::RowMajor>> spline_hierarchy(const Model& m) {
  std::vector<Eigen::SparseMatrix<double, Eigen::RowMajor>> out;
  const Model* fine = &m;
  Model coarse;
  for (int r = m.spec.refine - 1; r >= 0; --r) {
    CaseSpec spec = m.spec;
    spec.refine = r;
    Model next = build_model(spec);
    out.push_back(prolongation(next.body, *next.dofs, fine->body, *fine->dofs));
    coarse = std::move(next);
    fine = &coarse;
  }
  return out;
}
}  // namespace

ElementRange process_elements(const Model& m) {
  if (!uses_petsc(m)) return {};
  // Any cut will do: a pressure function belongs to the process holding the
  // first element of its support (engine/sparsity.hpp), which evaluates its
  // other elements again for it.
  const auto [b, e] = process_share(m.body.num_elements());
  return {b, e};
}

void sum_over_processes(Eigen::VectorXd& f) {
  if (!PetscSession::active() || PetscSession::size() == 1) return;
  MPI_Allreduce(MPI_IN_PLACE, f.data(), int(f.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);  // PETSc's world
}

ProcessShare elasticity_share(const Model& m) {
  if (!uses_petsc(m) || !PetscSession::active() || PetscSession::size() == 1) return {};
  ProcessShare share;
  share.elements = process_elements(m);
  // (an Allreduce's sum is the same on every process: each decides alike)
  share.sum = [](double* values, int count) {
    MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  };
  share.everywhere = [](bool mine) {
    int here = mine ? 1 : 0, all = 0;
    MPI_Allreduce(&here, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return all == 1;
  };
  return share;
}

ContactSolution solve_with_petsc(const Model& m, LinearSystem& sys, const WeightedGapOperator& op,
                                 const RigidModes& modes, const ContactSolverOptions& opt, LinearSolverRecord& record) {
  if (!PetscSession::active()) throw std::logic_error("the PETSc solver needs a PetscSession");
  PetscContactOptions po;
  po.contact = opt;
  po.stiffness = m.spec.E;
  po.dim = m.body.space_dim();
  po.spline_multigrid = m.spec.solver.spline_multigrid();
  if (m.spec.solver.algebraic_multigrid()) algebraic_multigrid_defaults();
  if (po.spline_multigrid) po.prolongations = spline_hierarchy(m);
  // The load is whole on every process: PETSc gets it once.
  const Eigen::VectorXd f_part = PetscSession::rank() == 0 ? sys.f : Eigen::VectorXd::Zero(sys.f.size()).eval();
  ContactSolution s;
  try {
    s = solve_contact_petsc(sys.K, f_part, op, modes, rigid_motions(m), po);
  } catch (const PetscOptionError& e) {
    throw InputError(fmt::format("{}: [solver] options: {}", m.spec.where({.table = "solver", .key = "options"}), e.what()));
  }
  record.type = "petsc";
  record.method = s.linear_solver;
  record.iterations = s.linear_iterations;
  record.ranks = s.ranks;
  record.peak_resident_all_ranks_gib = s.peak_resident_all_ranks_gib;
  return s;
}
ContactSolution solve_with_petsc_from_whole(const Model& m, const Eigen::SparseMatrix<double>& K,
                                            const Eigen::VectorXd& f, const WeightedGapOperator& op,
                                            const RigidModes& modes, const ContactSolverOptions& opt,
                                            LinearSolverRecord& record) {
  // the first process's share is all of it, the others' nothing (the shares sum to K)
  LinearSystem share;
  share.K = PetscSession::rank() == 0 ? K : Eigen::SparseMatrix<double>(K.rows(), K.cols());
  share.f = f;
  return solve_with_petsc(m, share, op, modes, opt, record);
}

namespace {
// PETSc's Newton backend with its option errors said as input errors.
class ReportingPetscNewtonSolver final : public LinearBackend {
 public:
  ReportingPetscNewtonSolver(std::string where, std::function<void()> after_first_solve, Eigen::MatrixXd near_null,
                             std::optional<std::vector<Eigen::SparseMatrix<double, Eigen::RowMajor>>> hierarchy)
      : where_(std::move(where)),
        after_first_solve_(std::move(after_first_solve)),
        solver_(std::move(near_null), std::move(hierarchy)) {}
  bool setup(const BlockJacobian& J) override {
    return reported([&] { return solver_.setup(J); });
  }
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance) override {
    const bool ok = reported([&] { return solver_.solve(b, x, tolerance); });
    if (after_first_solve_) std::exchange(after_first_solve_, nullptr)();
    return ok;
  }
  const std::string& why() const override { return solver_.why(); }
  const LinearSolveStats& stats() const override { return solver_.stats(); }
  double condition_estimate() const override { return solver_.condition_estimate(); }
  LinearBackendReport report() const override { return solver_.report(); }

 private:
  template <class F>
  bool reported(F&& f) {
    try {
      return f();
    } catch (const PetscOptionError& e) {
      throw InputError(fmt::format("{}: [solver] options: {}", where_, e.what()));
    }
  }
  std::string where_;
  std::function<void()> after_first_solve_;
  PetscNewtonSolver solver_;
};
}  // namespace

std::unique_ptr<LinearBackend> petsc_linear_backend(const Model& m, std::function<void()> after_first_solve) {
  if (!uses_petsc(m)) return nullptr;
  if (!PetscSession::active()) throw std::logic_error("the PETSc solver needs a PetscSession");
  if (m.spec.solver.algebraic_multigrid()) algebraic_multigrid_defaults();
  std::optional<std::vector<Eigen::SparseMatrix<double, Eigen::RowMajor>>> hierarchy;
  if (m.spec.solver.spline_multigrid()) hierarchy = spline_hierarchy(m);
  return std::make_unique<ReportingPetscNewtonSolver>(m.spec.where({.table = "solver", .key = "options"}),
                                                      std::move(after_first_solve), rigid_motions(m),
                                                      std::move(hierarchy));
}
#else
ContactSolution solve_with_petsc_from_whole(const Model& m, const Eigen::SparseMatrix<double>&,
                                            const Eigen::VectorXd&, const WeightedGapOperator&, const RigidModes&,
                                            const ContactSolverOptions&, LinearSolverRecord&) {
  throw InputError(fmt::format("{}: [solver] type = \"petsc\": this igac was built without PETSc "
                               "(`scripts/bootstrap.sh petsc` installs and builds it)", m.spec.path));
}
std::unique_ptr<LinearBackend> petsc_linear_backend(const Model& m, std::function<void()>) {
  if (!uses_petsc(m)) return nullptr;
  throw InputError(fmt::format("{}: [solver] type = \"petsc\": this igac was built without PETSc "
                               "(`scripts/bootstrap.sh petsc` installs and builds it)", m.spec.path));
}
ElementRange process_elements(const Model&) { return {}; }
ProcessShare elasticity_share(const Model&) { return {}; }
void sum_over_processes(Eigen::VectorXd&) {}
ContactSolution solve_with_petsc(const Model& m, LinearSystem&, const WeightedGapOperator&, const RigidModes&,
                                 const ContactSolverOptions&, LinearSolverRecord&) {
  throw InputError(fmt::format("{}: [solver] type = \"petsc\": this igac was built without PETSc "
                               "(`scripts/bootstrap.sh petsc` installs and builds it)", m.spec.path));
}
#endif

}  // namespace igac
