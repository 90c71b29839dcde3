// SPDX-License-Identifier: BSD-3-Clause
#include "solvers/petsc_multigrid.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <mpi.h>

#include "solvers/petsc_contact.hpp"

namespace igac {

using petsc::check;
using petsc::default_option;
using petsc::share;

namespace {

// Rows [row0, row0 + rows) of M (whole) into a new distributed AIJ matrix
// with the given local sizes; columns [col0, col0 + cols) are this
// process's diagonal block.
Mat distributed(const RowSparse& M, PetscInt row0, PetscInt rows, PetscInt col0, PetscInt cols) {
  Mat out = nullptr;
  check(MatCreate(PETSC_COMM_WORLD, &out), "matrix");
  check(MatSetSizes(out, rows, cols, PetscInt(M.rows()), PetscInt(M.cols())), "matrix");
  check(MatSetType(out, MATAIJ), "matrix");
  std::vector<PetscInt> d_nnz(rows, 0), o_nnz(rows, 0);
  for (PetscInt r = 0; r < rows; ++r)
    for (RowSparse::InnerIterator e(M, row0 + r); e; ++e)
      ++(e.col() >= col0 && e.col() < col0 + cols ? d_nnz : o_nnz)[r];
  check(MatXAIJSetPreallocation(out, 1, d_nnz.data(), o_nnz.data(), nullptr, nullptr), "matrix");
  std::vector<PetscInt> idx;
  for (PetscInt r = row0; r < row0 + rows; ++r) {
    idx.assign(M.innerIndexPtr() + M.outerIndexPtr()[r], M.innerIndexPtr() + M.outerIndexPtr()[r + 1]);
    if (!idx.empty())
      check(MatSetValues(out, 1, &r, PetscInt(idx.size()), idx.data(), M.valuePtr() + M.outerIndexPtr()[r],
                         INSERT_VALUES), "matrix");
  }
  check(MatAssemblyBegin(out, MAT_FINAL_ASSEMBLY), "matrix");
  check(MatAssemblyEnd(out, MAT_FINAL_ASSEMBLY), "matrix");
  return out;
}

Vec vector_without_array(PetscInt local, PetscInt global) {
  Vec v = nullptr;
  check(VecCreateMPIWithArray(PETSC_COMM_WORLD, 1, local, global, nullptr, &v), "vector");
  return v;
}

}  // namespace

SplineMultigrid::SplineMultigrid(Mat A, const RowSparse& G, const Eigen::VectorXd& W,
                                 const Eigen::VectorXd& inactive_diagonal, const petsc::SaddleLayout& L,
                                 const std::vector<RowSparse>& prolongations)
    : A_(A), layout_(L), G_(G), W_(W), inactive_(inactive_diagonal) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  // G_A: G's pattern, values per active set.
  B_.p = distributed(G_, L.l0 - L.n, L.local_l(), L.u0, L.local_u());
  check(VecCreateMPI(comm, L.local_l(), L.m, &d_), "vector");
  check(VecDuplicate(d_, &sinv_), "vector");
  check(VecDuplicate(d_, &tl_), "vector");
  check(VecCreateMPI(comm, L.local_u(), L.n, &tu_), "vector");
  xu_.p = vector_without_array(L.local_u(), L.n);
  yu_.p = vector_without_array(L.local_u(), L.n);
  xl_.p = vector_without_array(L.local_l(), L.m);
  yl_.p = vector_without_array(L.local_l(), L.m);

  // Interpolations, coarse to fine; the finest level's rows are A's.
  // -u_pc_mg_levels L keeps the L finest meshes (the coarsest of them then
  // solved directly).  The case's own count was checked against its
  // --refine before anything was built (model/solver_choice.cpp); the
  // coarser solves that start a run (nested iteration) or a study's
  // coarser levels have fewer meshes and take all of theirs.
  const PetscInt available = PetscInt(prolongations.size()) + 1;
  PetscInt wanted = available;
  PetscBool given = PETSC_FALSE;
  check(PetscOptionsGetInt(nullptr, "u_", "-pc_mg_levels", &wanted, &given), "options", true);
  if (given && wanted < 1)
    throw PetscOptionError(fmt::format("PETSc option -u_pc_mg_levels {}: must be at least 1", wanted));
  const bool fewer_than_asked = given && wanted > available;
  wanted = std::min(wanted, available);
  const int nl = int(wanted) - 1;
  P_.resize(nl);
  for (int k = 0; k < nl; ++k) {  // prolongations[k]: level nl - k from nl - k - 1
    const RowSparse& P = prolongations[k];
    const auto [r0, rows] = k == 0 ? std::pair<PetscInt, PetscInt>{L.u0, L.local_u()} : share(PetscInt(P.rows()));
    const auto [c0, cols] = share(PetscInt(P.cols()));
    P_[nl - 1 - k].p = distributed(P, r0, rows, c0, cols);
  }
  check(KSPCreate(comm, &mg_), "solver");
  check(KSPSetOptionsPrefix(mg_, "u_"), "solver");
  check(KSPSetType(mg_, KSPPREONLY), "solver");
  PC pc = nullptr;
  check(KSPGetPC(mg_, &pc), "solver");
  check(PCSetType(pc, PCMG), "solver");
  check(PCMGSetLevels(pc, nl + 1, nullptr), "solver");
  for (int l = 1; l <= nl; ++l) check(PCMGSetInterpolation(pc, l, P_[l - 1]), "solver");
  check(PCMGSetGalerkin(pc, PC_MG_GALERKIN_BOTH), "solver");
  check(KSPSetOperators(mg_, A_, A_), "solver");
  // Chebyshev on incomplete Cholesky (ICC(0) on each process's block):
  // point smoothers (Jacobi, SOR) lose a factor 2 per level on the sphere
  // octant, whose elements next to its collapsed axis grow thinner with
  // every refinement (docs/petsc.md, "Why these choices").
  // Reverse Cuthill-McKee inside ICC and 4 Chebyshev steps: on hertz3d
  // (K alone) far fewer iterations than natural order and 2 steps, the
  // more so the finer the mesh (measured: docs/petsc.md, "Why these
  // choices").
  default_option("-u_mg_levels_ksp_type", "chebyshev");
  default_option("-u_mg_levels_ksp_max_it", "4");
  // Several processes: additive Schwarz with two layers of overlap rather
  // than block Jacobi, whose blocks cut the strong couplings at every
  // process boundary (with two layers of overlap the Krylov iterations on
  // 2 processes are those of one process, for more memory; measured:
  // docs/petsc.md, "Why these choices").  One process: the same smoother,
  // without ASM's copy of the matrix.
  int processes = 1;
  MPI_Comm_size(comm, &processes);
  if (processes > 1) {
    default_option("-u_mg_levels_pc_type", "asm");
    default_option("-u_mg_levels_pc_asm_overlap", "2");
  } else {
    default_option("-u_mg_levels_pc_type", "bjacobi");
  }
  default_option("-u_mg_levels_sub_pc_type", "icc");
  default_option("-u_mg_levels_sub_pc_factor_mat_ordering_type", "rcm");
  // PCMG reads -u_pc_mg_levels too: a coarser solve shows it its own count
  // while it reads the options, and the user's value is put back.
  if (fewer_than_asked) {
    char asked[32] = {};
    check(PetscOptionsGetString(nullptr, "u_", "-pc_mg_levels", asked, sizeof asked, nullptr), "options");
    check(PetscOptionsSetValue(nullptr, "-u_pc_mg_levels", std::to_string(wanted).c_str()), "options");
    const PetscErrorCode read = KSPSetFromOptions(mg_);
    check(PetscOptionsSetValue(nullptr, "-u_pc_mg_levels", asked), "options");
    check(read, "options", true);
  } else {
    check(KSPSetFromOptions(mg_), "options", true);
  }
}

SplineMultigrid::~SplineMultigrid() = default;

void SplineMultigrid::set_active_set(const std::vector<char>& active) {
  const petsc::SaddleLayout& L = layout_;
  std::vector<PetscInt> cols;
  std::vector<PetscScalar> vals;
  PetscScalar *pd = nullptr, *ps = nullptr;
  check(VecGetArray(d_, &pd), "vector");
  check(VecGetArray(sinv_, &ps), "vector");
  for (PetscInt row = L.l0 - L.n; row < L.l1 - L.n; ++row) {
    cols.clear();
    vals.clear();
    for (RowSparse::InnerIterator e(G_, row); e; ++e) {
      cols.push_back(PetscInt(e.col()));
      vals.push_back(active[row] ? e.value() : 0.0);
    }
    if (!cols.empty())
      check(MatSetValues(B_, 1, &row, PetscInt(cols.size()), cols.data(), vals.data(), INSERT_VALUES), "matrix");
    const PetscInt i = row - (L.l0 - L.n);
    pd[i] = active[row] ? 0.0 : inactive_[row];
    ps[i] = active[row] ? -W_[row] : 1.0 / inactive_[row];
  }
  check(VecRestoreArray(sinv_, &ps), "vector");
  check(VecRestoreArray(d_, &pd), "vector");
  check(MatAssemblyBegin(B_, MAT_FINAL_ASSEMBLY), "matrix");
  check(MatAssemblyEnd(B_, MAT_FINAL_ASSEMBLY), "matrix");
}

bool SplineMultigrid::set_constraints(const RowSparse& G, const Eigen::VectorXd& W,
                                      const Eigen::VectorXd& inactive_diagonal) {
  const bool same = G.rows() == G_.rows() && G.cols() == G_.cols() && G.nonZeros() == G_.nonZeros() &&
                    std::equal(G.outerIndexPtr(), G.outerIndexPtr() + G.rows() + 1, G_.outerIndexPtr()) &&
                    std::equal(G.innerIndexPtr(), G.innerIndexPtr() + G.nonZeros(), G_.innerIndexPtr());
  if (!same) return false;
  G_ = G;
  W_ = W;
  inactive_ = inactive_diagonal;
  return true;
}

void SplineMultigrid::attach(KSP ksp) {
  const PetscInt local = layout_.r1 - layout_.r0, N = layout_.n + layout_.m;
  check(MatCreateShell(PETSC_COMM_WORLD, local, local, N, N, this, &S_), "matrix");
  check(MatShellSetOperation(S_, MATOP_MULT, (void (*)(void))mult), "matrix");
  // symmetric as A is (a follower load's Newton matrix is not)
  PetscBool known = PETSC_FALSE, symmetric = PETSC_FALSE;
  check(MatIsSymmetricKnown(A_, &known, &symmetric), "matrix");
  if (known && symmetric) check(MatSetOption(S_, MAT_SYMMETRIC, PETSC_TRUE), "matrix");
  check(KSPSetOperators(ksp, S_, S_), "solver");
  PC pc = nullptr;
  check(KSPGetPC(ksp, &pc), "solver");
  check(PCSetType(pc, PCSHELL), "solver");
  check(PCShellSetContext(pc, this), "solver");
  check(PCShellSetApply(pc, apply), "solver");
  check(PCShellSetName(pc, "spline multigrid (block triangular: MG on the displacements, -W on the multipliers)"),
        "solver");
}

Mat SplineMultigrid::shell() const { return S_; }

void SplineMultigrid::setup(bool rebuild) {
  check(KSPSetReusePreconditioner(mg_, rebuild ? PETSC_FALSE : PETSC_TRUE), "solver");
  check(KSPSetOperators(mg_, A_, A_), "solver");
  check(KSPSetUp(mg_), "solver setup", true);
}

std::string SplineMultigrid::setup_failure() const {
  PC pc = nullptr;
  check(KSPGetPC(mg_, &pc), "solver");
  PCFailedReason reason = PC_NOERROR;
  check(PCGetFailedReason(pc, &reason), "solver");
  return reason == PC_NOERROR ? std::string()
                              : fmt::format("singular Newton matrix (PETSc's spline multigrid: {})", PCFailedReasons[reason]);
}

// x and y as the work vectors xu_, xl_, yu_, yl_ (their u and lambda parts,
// without copies), then `part`, then everything given back.
PetscErrorCode SplineMultigrid::on_parts(Vec x, Vec y, PetscErrorCode (SplineMultigrid::*part)()) {
  PetscFunctionBeginUser;
  const PetscScalar* px = nullptr;
  PetscScalar* py = nullptr;
  PetscCall(VecGetArrayRead(x, &px));
  PetscCall(VecGetArray(y, &py));
  const PetscInt nu = layout_.local_u();
  PetscCall(VecPlaceArray(xu_, px));
  PetscCall(VecPlaceArray(xl_, px + nu));
  PetscCall(VecPlaceArray(yu_, py));
  PetscCall(VecPlaceArray(yl_, py + nu));
  PetscCall((this->*part)());
  for (Vec v : {xu_.p, xl_.p, yu_.p, yl_.p}) PetscCall(VecResetArray(v));
  PetscCall(VecRestoreArray(y, &py));
  PetscCall(VecRestoreArrayRead(x, &px));
  PetscFunctionReturn(0);
}

PetscErrorCode SplineMultigrid::operator_parts() {  // y = [A G_A^T; G_A D_I] x
  PetscFunctionBeginUser;
  PetscCall(MatMult(A_, xu_, yu_));
  PetscCall(MatMultTransposeAdd(B_, xl_, yu_, yu_));
  PetscCall(MatMult(B_, xu_, yl_));
  PetscCall(VecPointwiseMult(tl_, d_, xl_));
  PetscCall(VecAXPY(yl_, 1.0, tl_));
  PetscFunctionReturn(0);
}

PetscErrorCode SplineMultigrid::preconditioner_parts() {  // y = P^-1 x
  PetscFunctionBeginUser;
  PetscCall(VecPointwiseMult(yl_, sinv_, xl_));  // z_l = S~^-1 r_l
  PetscCall(MatMultTranspose(B_, yl_, tu_));
  PetscCall(VecAYPX(tu_, -1.0, xu_));    // r_u - G_A^T z_l
  PetscCall(KSPSolve(mg_, tu_, yu_));    // z_u = MG(r_u - G_A^T z_l)
  PetscFunctionReturn(0);
}

PetscErrorCode SplineMultigrid::mult(Mat S, Vec x, Vec y) {
  void* self = nullptr;
  PetscCall(MatShellGetContext(S, &self));
  return static_cast<SplineMultigrid*>(self)->on_parts(x, y, &SplineMultigrid::operator_parts);
}

PetscErrorCode SplineMultigrid::apply(PC pc, Vec r, Vec z) {
  void* self = nullptr;
  PetscCall(PCShellGetContext(pc, &self));
  return static_cast<SplineMultigrid*>(self)->on_parts(r, z, &SplineMultigrid::preconditioner_parts);
}

}  // namespace igac
