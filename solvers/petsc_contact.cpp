// SPDX-License-Identifier: BSD-3-Clause
#include "solvers/petsc_contact.hpp"

#include "engine/stopwatch.hpp"
#include "solvers/petsc_multigrid.hpp"
#include "solvers/petsc_support.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <omp.h>
#include <optional>
#include <petscksp.h>
#include <set>
#include <sys/resource.h>

namespace igac {
using namespace petsc;
namespace {

bool g_active = false;
std::string g_message;              // PETSc's own words for the first error of a chain
std::vector<std::string> g_defaults;  // options igac set (not the user's: never "unused")

PetscErrorCode keep_message(MPI_Comm, int, const char*, const char*, PetscErrorCode n, PetscErrorType p,
                            const char* mess, void*) {
  if (p == PETSC_ERROR_INITIAL) g_message = mess ? mess : "";
  return n;
}

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && (s.back() == ' ' || s.back() == '.')) s.pop_back();
  return s;
}

// Codes PETSc gives to an option it cannot take (unknown type, bad value,
// a combination it does not support).
bool is_option_error(PetscErrorCode e) {
  return e == PETSC_ERR_ARG_UNKNOWN_TYPE || e == PETSC_ERR_ARG_WRONG || e == PETSC_ERR_ARG_OUTOFRANGE ||
         e == PETSC_ERR_ARG_INCOMP || e == PETSC_ERR_SUP || e == PETSC_ERR_USER_INPUT ||
         e == PETSC_ERR_ARG_TYPENOTSET || e == PETSC_ERR_ARG_WRONGSTATE;
}


}  // namespace

namespace petsc {

void check(PetscErrorCode e, const char* what, bool options_phase) {
  if (!e) return;
  const char* text = nullptr;
  PetscErrorMessage(e, &text, nullptr);
  std::string msg = one_line(fmt::format("PETSc {}: {}{}", what, text ? text : "error",
                                         g_message.empty() ? std::string() : ": " + one_line(g_message)));
  g_message.clear();
  if (e == PETSC_ERR_MEM) throw std::bad_alloc();
  if (options_phase && is_option_error(e)) throw PetscOptionError(msg);
  throw std::runtime_error(msg);
}

void default_option(const char* name, const char* value) {
  PetscBool has = PETSC_FALSE;
  check(PetscOptionsHasName(nullptr, nullptr, name, &has), "options");
  if (has) return;
  check(PetscOptionsSetValue(nullptr, name, value), "options");
  g_defaults.emplace_back(name + 1);
}

std::pair<PetscInt, PetscInt> share(PetscInt n) {
  PetscInt local = PETSC_DECIDE, first = 0;
  check(PetscSplitOwnership(PETSC_COMM_WORLD, &local, &n), "layout");
  MPI_Exscan(&local, &first, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return {rank == 0 ? 0 : first, local};
}

// Options left unused after the first solve: misspelt, or for another solver.
void refuse_unused_options() {
  PetscInt count = 0;
  char** names = nullptr;
  char** values = nullptr;
  check(PetscOptionsLeftGet(nullptr, &count, &names, &values), "options");
  std::vector<std::string> unused;
  for (PetscInt i = 0; i < count; ++i) {
    const std::string name = names[i];
    const bool ours = std::find(g_defaults.begin(), g_defaults.end(), name) != g_defaults.end();
    const bool global = name.rfind("log", 0) == 0 || name.rfind("malloc", 0) == 0 || name == "options_left" ||
                        name == "no_signal_handler" || name.rfind("info", 0) == 0 || name == "memory_view";
    if (!ours && !global) unused.push_back("-" + name);
  }
  PetscOptionsLeftRestore(nullptr, &count, &names, &values);
  if (!unused.empty())
    throw PetscOptionError(fmt::format("PETSc option {} was not used by the solver (misspelt, or an option of "
                                       "another solver type)", unused.front()));
}

double peak_resident_gib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / double(1 << 20);
}

void set_near_null_space(const Eigen::MatrixXd& near_null, const SaddleLayout& L, SaddleFields& f) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const Eigen::Index columns = near_null.rows() == L.n ? near_null.cols() : 0;  // (other rows: none)
  f.null_vecs = std::vector<OwnedVec>(columns);
  std::vector<Vec> null_raw;
  for (Eigen::Index j = 0; j < columns; ++j) {
    Vec& v = f.null_vecs[j].p;
    check(VecCreateMPI(comm, L.local_u(), L.n, &v), "vector");
    PetscScalar* a = nullptr;
    check(VecGetArray(v, &a), "vector");
    for (PetscInt i = L.u0; i < L.u1; ++i) a[i - L.u0] = near_null(i, j);
    check(VecRestoreArray(v, &a), "vector");
    for (Vec w : null_raw) {  // Gram-Schmidt: PETSc wants them orthonormal
      PetscScalar d = 0;
      check(VecDot(v, w, &d), "vector");
      check(VecAXPY(v, -d, w), "vector");
    }
    PetscReal norm = 0;
    check(VecNormalize(v, &norm), "vector");
    if (norm > 0) null_raw.push_back(v);
  }
  check(MatNullSpaceCreate(comm, PETSC_FALSE, PetscInt(null_raw.size()), null_raw.data(), &f.near), "null space");
}

void set_fields(PC pc, Mat A, const Eigen::MatrixXd& near_null, const SaddleLayout& L, SaddleFields& f) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  f = {};
  if (L.m == 0) {  // the whole matrix is the field u
    char u_type[64] = "gamg";
    PetscBool given = PETSC_FALSE;
    check(PetscOptionsGetString(nullptr, nullptr, "-fieldsplit_u_pc_type", u_type, sizeof u_type, &given), "options");
    check(PCSetType(pc, u_type), "options", true);
    if (near_null.rows() != L.n) return;
    set_near_null_space(near_null, L, f);
    check(MatSetNearNullSpace(A, f.near), "null space");
    return;
  }
  check(ISCreateStride(comm, L.local_u(), L.u0, 1, &f.is_u), "index set");
  check(ISCreateStride(comm, L.local_l(), L.l0, 1, &f.is_l), "index set");
  set_near_null_space(near_null, L, f);
  check(PetscObjectCompose((PetscObject)(IS)f.is_u, "nearnullspace", (PetscObject)(MatNullSpace)f.near), "null space");
  check(PCFieldSplitSetIS(pc, "u", f.is_u), "options", true);
  check(PCFieldSplitSetIS(pc, "lambda", f.is_l), "options", true);
}

}  // namespace petsc

PetscSession::PetscSession(const std::string& options) {
  if (g_active) throw std::logic_error("one PetscSession per program");
  // igac reports errors itself; PETSc's signal handler would hide a crash's cause.
  PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr);
  check(PetscInitializeNoArguments(), "initialisation");
  g_active = true;
  PetscPushErrorHandler(keep_message, nullptr);
  try {
    check(PetscOptionsInsertString(nullptr, options.c_str()), "options", true);
  } catch (...) {
    PetscFinalize();
    g_active = false;
    throw;
  }
  // One process per core: unless told otherwise, the assembly threads share
  // the cores with the other processes.
  if (size() > 1 && !std::getenv("OMP_NUM_THREADS")) omp_set_num_threads(std::max(1, omp_get_num_procs() / size()));
}

PetscSession::~PetscSession() {
  if (!g_active) return;
  PetscFinalize();
  g_active = false;
}

bool PetscSession::active() { return g_active; }
int PetscSession::rank() {
  if (!g_active) return 0;
  int r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}
int PetscSession::size() {
  if (!g_active) return 1;
  int s = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &s);
  return s;
}

void algebraic_multigrid_defaults() {
  petsc::default_option("-ksp_type", "fgmres");
  petsc::default_option("-pc_type", "fieldsplit");
  petsc::default_option("-pc_fieldsplit_type", "schur");
  petsc::default_option("-pc_fieldsplit_schur_fact_type", "full");
  petsc::default_option("-pc_fieldsplit_schur_precondition", "selfp");
  petsc::default_option("-fieldsplit_u_ksp_type", "preonly");
  petsc::default_option("-fieldsplit_u_pc_type", "gamg");
  petsc::default_option("-fieldsplit_u_mg_levels_ksp_max_it", "4");
  petsc::default_option("-fieldsplit_lambda_ksp_type", "preonly");
  petsc::default_option("-fieldsplit_lambda_pc_type", "lu");
  petsc::default_option("-fieldsplit_lambda_pc_factor_mat_solver_type", "mumps");
}

std::pair<int, int> process_share(int n) {
  const long long r = PetscSession::rank(), s = PetscSession::size();
  return {int(n * r / s), int(n * (r + 1) / s)};
}

namespace {

using RowMat = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// Whether every entry of `sub`'s pattern is in K's (compressed, sorted).
bool contains_pattern(const Eigen::SparseMatrix<double>& K, const RowMat& sub) {
  if (!K.isCompressed() || K.rows() != sub.rows() || K.cols() != sub.cols()) return false;
  for (int r = 0; r < sub.outerSize(); ++r) {
    const int* first = K.innerIndexPtr() + K.outerIndexPtr()[r];
    const int* past = K.innerIndexPtr() + K.outerIndexPtr()[r + 1];
    for (RowMat::InnerIterator e(sub, r); e; ++e)
      if (!std::binary_search(first, past, int(e.col()))) return false;
  }
  return true;
}

// The assembled matrix: K (this process's elements, any rows) plus, on the
// rows this process owns, the pattern of the augmentation G^T G (all
// multipliers) and, for the whole saddle-point matrix, the columns G^T and
// the rows [G D].  Every entry of the matrix's life is in the pattern.
// `saddle` false: the displacement block alone (n x n, A's rows [u0, u1)).
//
// On one process, the displacement block alone and the contact pattern
// inside K's: PETSc's matrix on K's arrays (no copy; K must outlive it).
// Otherwise K is copied and emptied.
//
// Preallocation from per-row counts: every process counts the entries of
// its elements' K in every row (diagonal or off-diagonal block of the
// row's owner) and the counts are summed.  Rows shared by two processes'
// elements are over-counted (a few slots unused); no hash table of the
// whole pattern is built beside K (MATPREALLOCATOR's, as before).
Mat assemble_matrix(Eigen::SparseMatrix<double>& Kp, const RowMat& G, const RowMat& Gt, const RowMat& GtG,
                    const SaddleLayout& L, bool saddle) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const PetscInt size = saddle ? L.n + L.m : L.n, local = saddle ? L.r1 - L.r0 : L.local_u();
  const PetscInt n = L.n, first = saddle ? L.r0 : L.u0;
  int procs = 1;
  MPI_Comm_size(comm, &procs);
  if (procs == 1 && !saddle && contains_pattern(Kp, GtG)) {
    // The displacement block on one process: PETSc's matrix on K's own
    // arrays (symmetric K: its compressed columns are its rows), no copy
    // (the peak it saves is measured in docs/petsc.md, "Measured").  Kp
    // must outlive it.
    Mat A = nullptr;
    check(MatCreateSeqAIJWithArrays(comm, n, n, Kp.outerIndexPtr(), Kp.innerIndexPtr(), Kp.valuePtr(), &A),
          "matrix");
    check(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE), "matrix");
    check(MatSetOption(A, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "matrix");
    check(MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "matrix");
    return A;
  }
  std::vector<PetscInt> starts(procs + 1, 0);
  MPI_Allgather(&local, 1, MPIU_INT, starts.data() + 1, 1, MPIU_INT, comm);
  for (int q = 0; q < procs; ++q) starts[q + 1] += starts[q];
  auto owner_range = [&](PetscInt row) {
    const int q = int(std::upper_bound(starts.begin(), starts.end(), row) - starts.begin()) - 1;
    return std::pair{starts[q], starts[q + 1]};
  };
  std::vector<PetscInt> d_all(n, 0), o_all(n, 0);
  for (PetscInt c = 0; c < n; ++c) {  // K symmetric: column c is row c
    const auto [lo, hi] = owner_range(c);
    for (int e = Kp.outerIndexPtr()[c]; e < Kp.outerIndexPtr()[c + 1]; ++e) {
      const PetscInt r = Kp.innerIndexPtr()[e];
      ++(r >= lo && r < hi ? d_all : o_all)[c];
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, d_all.data(), int(n), MPIU_INT, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, o_all.data(), int(n), MPIU_INT, MPI_SUM, comm);
  // The contact pattern of the owned rows: (row, column) lists, zeros first.
  std::vector<std::vector<PetscInt>> contact(local);
  for (PetscInt row = first; row < first + local; ++row) {
    std::vector<PetscInt>& cols = contact[row - first];
    if (row < n) {
      for (RowMat::InnerIterator it(GtG, row); it; ++it) cols.push_back(PetscInt(it.col()));
      if (saddle)
        for (RowMat::InnerIterator it(Gt, row); it; ++it) cols.push_back(n + PetscInt(it.col()));
    } else {
      for (RowMat::InnerIterator it(G, row - n); it; ++it) cols.push_back(PetscInt(it.col()));
      cols.push_back(row);
    }
  }
  std::vector<PetscInt> d_nnz(local), o_nnz(local);
  for (PetscInt i = 0; i < local; ++i) {
    const PetscInt row = first + i;
    PetscInt d = row < n ? d_all[row] : 0, o = row < n ? o_all[row] : 0;
    for (PetscInt c : contact[i]) ++(c >= first && c < first + local ? d : o);
    d_nnz[i] = std::min(d, local);
    o_nnz[i] = std::min(o, size - local);
  }
  d_all = {};
  o_all = {};
  Mat A = nullptr;
  check(MatCreate(comm, &A), "matrix");
  check(MatSetType(A, MATAIJ), "matrix");
  check(MatSetSizes(A, local, local, size, size), "matrix");
  check(MatXAIJSetPreallocation(A, 1, d_nnz.data(), o_nnz.data(), nullptr, nullptr), "matrix");
  check(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE), "matrix");
  check(MatSetOption(A, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "matrix");
  std::vector<PetscInt> cols;
  for (PetscInt c = 0; c < n; ++c) {
    const int b = Kp.outerIndexPtr()[c], e = Kp.outerIndexPtr()[c + 1];
    if (b == e) continue;
    cols.assign(Kp.innerIndexPtr() + b, Kp.innerIndexPtr() + e);
    check(MatSetValues(A, 1, &c, e - b, cols.data(), Kp.valuePtr() + b, ADD_VALUES), "matrix");
  }
  Kp = Eigen::SparseMatrix<double>();  // PETSc has it now
  std::vector<PetscScalar> zeros;
  for (PetscInt i = 0; i < local; ++i) {
    if (contact[i].empty()) continue;
    const PetscInt row = first + i;
    zeros.assign(contact[i].size(), 0.0);
    check(MatSetValues(A, 1, &row, PetscInt(contact[i].size()), contact[i].data(), zeros.data(), ADD_VALUES),
          "matrix");
  }
  check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "matrix");
  check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "matrix");
  check(MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "matrix");
  return A;
}

// The rows [G_A D_I] and the columns G_A^T of the whole saddle-point matrix
// for this active set (owned rows only; flushed, not final).
void set_contact_rows(Mat A, const RowMat& G, const RowMat& Gt, const std::vector<char>& active,
                      const Eigen::VectorXd& inactive_diagonal, const SaddleLayout& L) {
  std::vector<PetscInt> cols;
  std::vector<PetscScalar> vals;
  for (PetscInt row = L.l0; row < L.l1; ++row) {  // [G_A  D_I]
    const PetscInt K = row - L.n;
    cols.clear();
    vals.clear();
    for (RowMat::InnerIterator e(G, K); e; ++e) {
      cols.push_back(PetscInt(e.col()));
      vals.push_back(active[K] ? e.value() : 0.0);
    }
    cols.push_back(row);
    vals.push_back(active[K] ? 0.0 : inactive_diagonal[K]);
    check(MatSetValues(A, 1, &row, PetscInt(cols.size()), cols.data(), vals.data(), INSERT_VALUES), "matrix");
  }
  for (PetscInt row = L.u0; row < L.u1; ++row) {  // G_A^T
    cols.clear();
    vals.clear();
    for (RowMat::InnerIterator e(Gt, row); e; ++e) {
      cols.push_back(L.n + PetscInt(e.col()));
      vals.push_back(active[e.col()] ? e.value() : 0.0);
    }
    if (!cols.empty())
      check(MatSetValues(A, 1, &row, PetscInt(cols.size()), cols.data(), vals.data(), INSERT_VALUES), "matrix");
  }
  check(MatAssemblyBegin(A, MAT_FLUSH_ASSEMBLY), "matrix");
  check(MatAssemblyEnd(A, MAT_FLUSH_ASSEMBLY), "matrix");
}

}  // namespace

ContactSolution solve_contact_petsc(Eigen::SparseMatrix<double>& Kp, const Eigen::VectorXd& f_part,
                                    const WeightedGapOperator& op, const RigidModes& modes,
                                    const Eigen::MatrixXd& near_null, const PetscContactOptions& o) {
  if (!g_active) throw std::logic_error("solve_contact_petsc without a PetscSession");
  const MPI_Comm comm = PETSC_COMM_WORLD;
  const PetscInt n = PetscInt(Kp.rows()), m = PetscInt(op.weights.size()), N = n + m;
  const int k = int(modes.modes.cols());
  const bool multigrid = o.spline_multigrid;
  ContactSolution sol;
  sol.ranks = PetscSession::size();
  Stopwatch t0;

  // Augmentation weights W_K = E / h_K^d, h_K from the multiplier's support
  // measure int B_K ~ h^(d-1): G^T W G has the magnitude of K on the face.
  // An inactive multiplier's row is D_KK l_K = 0, D_KK = W_K (int B_K)^2.
  Eigen::VectorXd W(m), D(m);
  for (PetscInt K = 0; K < m; ++K) {
    W[K] = o.stiffness / std::pow(std::pow(op.weights[K], 1.0 / (o.dim - 1)), o.dim);
    D[K] = W[K] * op.weights[K] * op.weights[K];
  }
  const RowMat& G = op.G;
  const RowMat Gt = RowMat(G.transpose());
  const RowMat GtG = RowMat(Gt * G);  // pattern of the augmentation (all multipliers)

  const auto [r0, rows] = share(N);
  const SaddleLayout L = SaddleLayout::of(n, m, r0, r0 + rows);
  // The assembled matrix: the whole saddle-point matrix, or (multigrid) its
  // displacement block, the rest applied by SplineMultigrid's shell.
  OwnedMat A;
  A.p = assemble_matrix(Kp, G, Gt, GtG, L, !multigrid);
  std::optional<SplineMultigrid> mg;
  // ICC(0) in quotient minimum degree order in 2D: in reverse Cuthill-McKee
  // order (3D's choice) it broke down on hertz2d's graded level 3 (measured:
  // docs/petsc.md, "Why the spline multigrid loses in 2D").
  if (multigrid && o.dim == 2) default_option("-u_mg_levels_sub_pc_factor_mat_ordering_type", "qmd");
  if (multigrid) mg.emplace(A, G, W, D, L, o.prolongations);

  OwnedKSP ksp;
  check(KSPCreate(comm, &ksp), "solver");
  if (multigrid) {
    PetscBool has = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, nullptr, "-pc_type", &has), "options");
    if (has)
      throw PetscOptionError("PETSc option -pc_type: the spline multigrid is the preconditioner (its own options "
                             "start with -u_, e.g. -u_mg_levels_pc_type sor)");
    mg->attach(ksp);
    // Multigrid with a Chebyshev smoother is a fixed linear operator, but a
    // user's inner Krylov (-u_ksp_type cg) would not be: flexible GMRES.
    default_option("-ksp_type", "fgmres");  // restart 30: 60 vectors (~25 iterations per solve measured)
  } else {
    check(KSPSetOperators(ksp, A, A), "solver");
    default_option("-ksp_type", "preonly");
    default_option("-pc_type", "cholesky");
    default_option("-pc_factor_mat_solver_type", "mumps");
    // The symbolic analysis is reused over the active-set iterations while
    // the pivots of the indefinite matrix move: room for delayed pivots
    // (MUMPS's default +20 % ran out of memory on hertz3d, 2 processes).
    default_option("-mat_mumps_icntl_14", "100");
  }
  // Tight enough that a Krylov solution matches the direct one to 1e-8
  // (the multigrid path: 1e-12, p0 on hertz3d was 1.2e-8 off at 1e-11).
  // The multigrid path solves to kLoose while the active set moves (it only
  // decides signs of lambda and of the gaps), then once more to kTight for
  // the active set that repeats itself (checked to repeat again).
  const double kTight = multigrid ? 1e-12 : 1e-11, kLoose = 1e-6;
  bool loose = multigrid;
  check(KSPSetTolerances(ksp, loose ? kLoose : kTight, 1e-50, PETSC_DEFAULT, 2000), "solver");
  check(KSPSetFromOptions(ksp), "options", true);
  PC pc = nullptr;
  check(KSPGetPC(ksp, &pc), "solver");
  KSPType ksp_type = nullptr;
  PCType pc_type = nullptr;
  check(KSPGetType(ksp, &ksp_type), "solver");
  check(PCGetType(pc, &pc_type), "solver");
  SaddleFields fields;
  if (pc_type && std::string(pc_type) == PCFIELDSPLIT) set_fields(pc, A, near_null, L, fields);
  const bool preonly = ksp_type && std::string(ksp_type) == KSPPREONLY;
  if (!preonly) check(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE), "solver");
  const Mat op_mat = multigrid ? mg->shell() : Mat(A);

  OwnedVec x, b, bf, residual;
  check(MatCreateVecs(op_mat, &x, &b), "vector");
  check(VecDuplicate(b, &bf), "vector");
  check(VecDuplicate(b, &residual), "vector");
  // Whatever the options made the Krylov solver stop at, a result is only a
  // solution when the saddle-point system's true residual |b - A x| / |b|
  // is at most this (an -ksp_rtol of 0.9 stopped at 0.9 and was reported
  // converged).
  constexpr double kAcceptedResidual = 1e-6;
  double relative_residual = 0;
  bool settled = false;  // the last iteration repeated its set
  check(VecSet(x, 0.0), "vector");
  {  // f in u's rows (numbered as in the saddle-point system: u first)
    std::vector<PetscInt> idx;
    std::vector<PetscScalar> val;
    for (PetscInt i = 0; i < n; ++i)
      if (f_part[i] != 0.0) {
        idx.push_back(i);
        val.push_back(f_part[i]);
      }
    check(VecSet(bf, 0.0), "vector");
    if (multigrid) {  // the shell's vectors are ordered [u, lambda] per process, not globally
      OwnedVec fu;
      check(VecCreateMPI(comm, L.local_u(), n, &fu), "vector");
      check(VecSetValues(fu, PetscInt(idx.size()), idx.data(), val.data(), ADD_VALUES), "vector");
      check(VecAssemblyBegin(fu), "vector");
      check(VecAssemblyEnd(fu), "vector");
      const PetscScalar* pf = nullptr;
      PetscScalar* pb = nullptr;
      check(VecGetArrayRead(fu, &pf), "vector");
      check(VecGetArray(bf, &pb), "vector");
      std::copy(pf, pf + L.local_u(), pb);
      check(VecRestoreArray(bf, &pb), "vector");
      check(VecRestoreArrayRead(fu, &pf), "vector");
    } else {
      check(VecSetValues(bf, PetscInt(idx.size()), idx.data(), val.data(), ADD_VALUES), "vector");
      check(VecAssemblyBegin(bf), "vector");
      check(VecAssemblyEnd(bf), "vector");
    }
  }
  const double assembly_s = t0.seconds();

  // The solution to every process: u and lambda gathered separately (the
  // shell's vectors interleave them process by process).
  OwnedVec xu, xl, u_all, l_all;
  OwnedScatter u_to_all, l_to_all;
  check(VecCreateMPIWithArray(comm, 1, L.local_u(), n, nullptr, &xu), "vector");
  check(VecCreateMPIWithArray(comm, 1, L.local_l(), m, nullptr, &xl), "vector");
  check(VecScatterCreateToAll(xu, &u_to_all, &u_all), "vector");
  check(VecScatterCreateToAll(xl, &l_to_all, &l_all), "vector");

  std::vector<char> active = initial_active_set(op, k, o.contact);
  if (o.contact.initial_u.size() == n) {  // a start from the coarser mesh: the first guess
    PetscScalar* px = nullptr;
    check(VecGetArray(x, &px), "vector");
    for (PetscInt row = L.u0; row < L.u1; ++row) px[row - L.u0] = o.contact.initial_u[row];
    if (o.contact.initial_lambda.size() == m)
      for (PetscInt row = L.l0; row < L.l1; ++row) px[L.local_u() + row - L.l0] = o.contact.initial_lambda[row - n];
    check(VecRestoreArray(x, &px), "vector");
  }
  std::set<std::vector<char>> seen;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m), u = Eigen::VectorXd::Zero(n);
  RowMat aug_prev(n, n);  // G_A^T W G_A in the matrix now
  double setup_s = 0, solve_s = 0;
  int built_for = -1;  // active-set size the multigrid hierarchy was built for
  for (int it = 0; it < o.contact.max_iterations; ++it) {
    sol.active_set_sizes.push_back(int(std::count(active.begin(), active.end(), 1)));
    // Contact rows and columns for this active set (owned rows only).
    Stopwatch ts;
    Eigen::VectorXd wa(m), g0a(m);
    for (PetscInt K = 0; K < m; ++K) {
      wa[K] = active[K] ? W[K] : 0.0;
      g0a[K] = active[K] ? op.g0[K] : 0.0;
    }
    if (multigrid)
      mg->set_active_set(active);
    else
      set_contact_rows(A, G, Gt, active, D, L);
    const RowMat aug = RowMat(Gt * wa.asDiagonal() * G);
    const RowMat delta = RowMat(aug - aug_prev);
    std::vector<PetscInt> cols;
    std::vector<PetscScalar> vals;
    for (PetscInt row = L.u0; row < L.u1; ++row) {  // + G_A^T W G_A - (the previous one)
      cols.clear();
      vals.clear();
      for (RowMat::InnerIterator e(delta, row); e; ++e) {
        cols.push_back(PetscInt(e.col()));
        vals.push_back(e.value());
      }
      if (!cols.empty())
        check(MatSetValues(A, 1, &row, PetscInt(cols.size()), cols.data(), vals.data(), ADD_VALUES), "matrix");
    }
    check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "matrix");
    check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "matrix");
    aug_prev = aug;
    // Right-hand side [f - G_A^T W g0_A; -g0_A], and the start: the last
    // solution with the inactive multipliers at zero.
    const Eigen::VectorXd rhs_u = -(Gt * wa.cwiseProduct(g0a));
    check(VecCopy(bf, b), "vector");
    PetscScalar *pb = nullptr, *px = nullptr;
    check(VecGetArray(b, &pb), "vector");
    check(VecGetArray(x, &px), "vector");
    for (PetscInt row = L.u0; row < L.u1; ++row) pb[row - L.u0] += rhs_u[row];
    for (PetscInt row = L.l0; row < L.l1; ++row) {
      const PetscInt i = L.local_u() + row - L.l0;
      pb[i] = -g0a[row - n];
      if (!active[row - n]) px[i] = 0.0;
    }
    check(VecRestoreArray(x, &px), "vector");
    check(VecRestoreArray(b, &pb), "vector");
    sol.schur_s += ts.seconds();  // (here: the contact rows' assembly)

    ts.restart();
    check(KSPSetOperators(ksp, op_mat, op_mat), "solver");
    check(KSPSetUp(ksp), "solver setup", it == 0);
    if (multigrid) {
      // The hierarchy (Galerkin products, ICC factors, Chebyshev bounds) is
      // rebuilt when the active set has changed by a fifth since it was
      // built: the augmentation only touches the contact face, and a
      // hierarchy of a nearby set preconditions as well (hertz3d level 2:
      // the same iterations per solve, setup 6 s instead of 10 s).
      const int now = sol.active_set_sizes.back();
      const bool rebuild = built_for < 0 || std::abs(now - built_for) > 0.2 * std::max(built_for, 1);
      mg->setup(rebuild);
      if (rebuild) built_for = now;
    }
    setup_s += ts.seconds();
    ts.restart();
    check(KSPSolve(ksp, b, x), "solve", it == 0);
    solve_s += ts.seconds();
    if (it == 0) refuse_unused_options();
    KSPConvergedReason reason;
    PetscInt iterations = 0;
    check(KSPGetConvergedReason(ksp, &reason), "solver");
    check(KSPGetIterationNumber(ksp, &iterations), "solver");
    sol.linear_iterations.push_back(int(iterations));
    {  // the true residual of this solve
      PetscReal r_norm = 0, b_norm = 0;
      check(MatMult(op_mat, x, residual), "solve");
      check(VecAYPX(residual, -1.0, b), "vector");
      check(VecNorm(residual, NORM_2, &r_norm), "vector");
      check(VecNorm(b, NORM_2, &b_norm), "vector");
      relative_residual = b_norm > 0 ? double(r_norm / b_norm) : double(r_norm);
    }

    const PetscScalar* pa = nullptr;
    check(VecGetArrayRead(x, &pa), "vector");
    check(VecPlaceArray(xu, pa), "vector");
    check(VecPlaceArray(xl, pa + L.local_u()), "vector");
    check(VecScatterBegin(u_to_all, xu, u_all, INSERT_VALUES, SCATTER_FORWARD), "vector");
    check(VecScatterEnd(u_to_all, xu, u_all, INSERT_VALUES, SCATTER_FORWARD), "vector");
    check(VecScatterBegin(l_to_all, xl, l_all, INSERT_VALUES, SCATTER_FORWARD), "vector");
    check(VecScatterEnd(l_to_all, xl, l_all, INSERT_VALUES, SCATTER_FORWARD), "vector");
    check(VecResetArray(xu), "vector");
    check(VecResetArray(xl), "vector");
    check(VecRestoreArrayRead(x, &pa), "vector");
    check(VecGetArrayRead(u_all, &pa), "vector");
    u = Eigen::Map<const Eigen::VectorXd>(pa, n);
    check(VecRestoreArrayRead(u_all, &pa), "vector");
    check(VecGetArrayRead(l_all, &pa), "vector");
    lambda = Eigen::Map<const Eigen::VectorXd>(pa, m);
    check(VecRestoreArrayRead(l_all, &pa), "vector");
    for (PetscInt K = 0; K < m; ++K)
      if (!active[K]) lambda[K] = 0.0;
    const Eigen::VectorXd gap = (op.g0 + G * u).cwiseQuotient(op.weights);
    sol.weighted_gap = gap;
    if (reason < 0) {
      PCFailedReason pc_reason = PC_NOERROR;
      PCGetFailedReason(pc, &pc_reason);
      sol.status = fmt::format("failed: the PETSc linear solve did not converge in active-set iteration {} ({}{}, "
                               "{} iterations)",
                               it + 1, KSPConvergedReasons[reason],
                               pc_reason != PC_NOERROR ? std::string(", ") + PCFailedReasons[pc_reason] : "",
                               iterations);
      break;
    }
    int forced = 0;
    const std::vector<char> next = next_active_set(lambda, gap, active, k, o.contact.complementarity_scale, &forced);
    if (loose && next == active) {  // the same set again, now solved tightly (not a new iteration)
      loose = false;
      check(KSPSetTolerances(ksp, kTight, 1e-50, PETSC_DEFAULT, 2000), "solver");
      sol.active_set_sizes.pop_back();
      --it;
      continue;
    }
    settled = next == active;
    if (settle_active_set(next, active, seen, it, sol, o.contact, forced)) break;
  }
  if (!sol.converged && sol.status.empty())
    sol.status = fmt::format("active set not settled in {} iterations", o.contact.max_iterations);
  // A settled set (converged, or holding the body by a pulling multiplier)
  // from a solve that stopped early proves nothing: the residual first.
  if (settled && !(relative_residual <= kAcceptedResidual)) {
    sol.converged = false;
    sol.status = fmt::format("failed: the last PETSc solve stopped at a relative residual of {:.2g} (more than {:g}): "
                             "not a solution; tighten the Krylov tolerance (-ksp_rtol) or change the solver options",
                             relative_residual, kAcceptedResidual);
  }
  sol.u = u;
  sol.lambda = lambda;
  sol.active = active;
  sol.factorize_s = setup_s;
  sol.iterations_s = solve_s;
  sol.schur_s += assembly_s;
  sol.linear_solver = multigrid ? fmt::format("{} + spline multigrid ({} levels)", ksp_type ? ksp_type : "?",
                                              mg->levels())
                                : fmt::format("{} + {}", ksp_type ? ksp_type : "?", pc_type ? pc_type : "?");
  if (pc_type && (std::string(pc_type) == PCLU || std::string(pc_type) == PCCHOLESKY)) {
    MatSolverType st = nullptr;
    if (!PCFactorGetMatSolverType(pc, &st) && st) sol.linear_solver += fmt::format(" ({})", st);
  }
  double mine = peak_resident_gib(), all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, comm);
  sol.peak_resident_all_ranks_gib = all;
  return sol;
}

}  // namespace igac
