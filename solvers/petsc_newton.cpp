// SPDX-License-Identifier: BSD-3-Clause
#include "solvers/petsc_newton.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <optional>
#include <petscksp.h>
#include <vector>

#include "engine/stopwatch.hpp"
#include "solvers/petsc_contact.hpp"
#include "solvers/petsc_multigrid.hpp"
#include "solvers/petsc_support.hpp"

namespace igac {
using namespace petsc;

namespace {
using RowMat = Eigen::SparseMatrix<double, Eigen::RowMajor>;
// An iterative solve that was asked for "as tight as it goes" (tolerance 0:
// the tangent predictor) stops here, relative to |b|.
constexpr double kTight = 1e-11;
}  // namespace

struct PetscNewtonSolver::Impl {
  const BlockJacobian* J = nullptr;
  BlockJacobian one_block;  // J as one block when its rows combine (as_one_block)
  PetscInt N = -1, first = 0, local = 0;  // rows [first, first + local) are this process's
  PetscInt m = 0;                         // of which the last m are multipliers
  bool general = false;                   // (BlockJacobian::general)
  // The owned rows' pattern (row pointers from 0, global columns).
  std::vector<PetscInt> row_ptr, cols;
  OwnedMat A;
  OwnedKSP ksp;
  OwnedVec b, x, x_all;
  OwnedScatter to_all;
  bool solved_once = false;
  std::vector<int> iterations;
  std::string method;
  // The symmetric form (below) of the last setup, and the one the KSP was made for.
  bool symmetric = false, ksp_symmetric = false;
  // The active rows divided by their scale and the inactive multipliers'
  // columns moved to the right-hand side (the symmetric form's constraint
  // rows; the spline multigrid's shell has that form whatever K is).
  bool constraint_form = false;
  // An iterative solve (the options name a PC that is not a factorisation):
  // the active rows are added to the displacement block as an augmented
  // Lagrangian (below), the field split gets its fields.
  bool augmented = false;
  Eigen::VectorXd W;            // the augmentation's weights of the last setup (0: inactive)
  Eigen::MatrixXd near_null;    // rigid motions of the displacements (n rows; none: n x 0)
  SaddleFields fields;
  // The spline multigrid (given a hierarchy): A is the displacement block
  // K + B_A^T W B_A alone, the rest applied by the multigrid's shell.
  std::optional<std::vector<RowMat>> hierarchy;
  std::optional<SplineMultigrid> mg;
  SaddleLayout layout;
  // A Krylov solve stops on the residual of J itself (stop_test).
  double stop_at = 0;       // |b| (J's condensed right-hand side) times the tolerance
  OwnedVec work_t, work_r;  // KSPBuildResidual's

  // Whether J has a symmetric form: K symmetric (no follower load, no slip
  // rows, no coupling outside K), to round-off of its largest entry.  Then
  // each active row s_k B_k du = b_k is divided by s_k, and each inactive
  // multiplier's column B_k^T is moved to the right-hand side (dl_k = b_k /
  // d_k is its row): the same solution, a symmetric (indefinite) matrix of
  // the same pattern, which MUMPS factorises as L D L^T (about half LU's work).
  static bool has_symmetric_form(const BlockJacobian& J) {
    if (J.general || J.K_coupling.nonZeros() > 0 || J.K.rows() != J.K.cols()) return false;
    // K(r, c) against K(c, r), found in column r (compressed, rows
    // increasing): no transpose of the whole
    const Eigen::SparseMatrix<double>& K = J.K;
    if (!K.isCompressed()) return false;
    const int* outer = K.outerIndexPtr();
    const int* inner = K.innerIndexPtr();
    const double* value = K.valuePtr();
    double largest = 0, skew = 0;
    for (int c = 0; c < K.outerSize(); ++c)
      for (int k = outer[c]; k < outer[c + 1]; ++k) {
        const int r = inner[k];
        largest = std::max(largest, std::abs(value[k]));
        const int* at = std::lower_bound(inner + outer[r], inner + outer[r + 1], c);
        const double mirror = at != inner + outer[r + 1] && *at == c ? value[at - inner] : 0.0;
        skew = std::max(skew, std::abs(value[k] - mirror));
      }
    return skew <= 1e-13 * largest;
  }

  // The augmented Lagrangian of the active rows: B_A du = c_A (an active row
  // s_k B_k du = b_k divided by s_k) added to the displacement rows as
  // B_A^T W (B_A du - c_A) = 0, which leaves the solution unchanged and
  // makes the displacement block definite where only contact holds the body
  // (Hertz: K alone has the free vertical translation in its kernel), which
  // algebraic multigrid needs.  W_k puts W_k B_k^T B_k at the size of K's
  // diagonal on B_k's support.  Every constraint's product is in the pattern
  // (zero while inactive), so that the pattern stays as the set changes.
  // `size`: the rows and columns of the matrix it is added to (n + m, or
  // the displacement block's n).
  RowMat augmentation(const BlockJacobian& J, int size) {
    const int m = int(J.B.rows());
    W = Eigen::VectorXd::Zero(m);
    const Eigen::VectorXd diagonal = J.K.diagonal();
    std::vector<Eigen::Triplet<double>> t;
    for (int k = 0; k < m; ++k) {
      double diag_sum = 0, largest = 0;
      int count = 0;
      for (RowMat::InnerIterator it(J.B, k); it; ++it, ++count) {
        diag_sum += std::abs(diagonal[it.col()]);
        largest = std::max(largest, it.value() * it.value());
      }
      if (J.s[k] != 0 && largest > 0) W[k] = diag_sum / count / largest;
      for (RowMat::InnerIterator i(J.B, k); i; ++i)
        for (RowMat::InnerIterator j(J.B, k); j; ++j) t.emplace_back(i.col(), j.col(), W[k] * i.value() * j.value());
    }
    RowMat A(size, size);
    A.setFromTriplets(t.begin(), t.end());
    return A;
  }

  // This process's rows of the condensed J (in the symmetric form where it
  // has one); true when their pattern is the last one's.
  bool take_rows(const BlockJacobian& blocks, RowMat& R) {
    symmetric = has_symmetric_form(blocks);
    constraint_form = symmetric;
    m = PetscInt(blocks.B.rows());
    general = blocks.general;
    const int n = int(blocks.K.rows()), size = n + int(m);
    if (new_size(PetscInt(size)) || symmetric != ksp_symmetric) {
      row_ptr.clear();
      ksp = {};  // a KSP keeps its first operator's sizes and its factorisation's kind
    }
    // this process's rows of the condensed J (every process holds J: no copy of the whole)
    std::optional<RowMat> extra;
    if (augmented && m > 0) extra = augmentation(blocks, size);
    R = condensed_rows(blocks, int(first), int(first + local), -1, extra ? &*extra : nullptr);
    if (symmetric)
      for (int r = 0; r < R.outerSize(); ++r) {
        const int row = int(first) + r;
        for (RowMat::InnerIterator it(R, r); it; ++it) {
          if (row >= n && blocks.s[row - n] != 0) it.valueRef() /= blocks.s[row - n];  // an active row
          // an inactive column (moved to the right-hand side; the augmentation is zero there)
          if (row < n && it.col() >= n && blocks.s[it.col() - n] == 0) it.valueRef() = 0;
        }
      }
    return keep_rows(R);
  }

  // A new number of unknowns N (friction's iterations: they come and go):
  // the rows shared anew, the vectors dropped.
  bool new_size(PetscInt rows) {
    if (rows == N) return false;
    N = rows;
    std::tie(first, local) = share(N);
    x = {};
    b = {};
    work_t = {};
    work_r = {};
    x_all = {};
    to_all = {};
    return true;
  }

  // R (this process's rows, all columns) as its part of the matrix: its
  // pattern kept to compare with the next; true when every process's
  // pattern is the last one's.
  bool keep_rows(const RowMat& R) {
    const int* outer = R.outerIndexPtr();
    const PetscInt count = R.rows();
    const int nnz = outer[count];
    bool same = PetscInt(row_ptr.size()) == count + 1 && PetscInt(cols.size()) == nnz;
    for (PetscInt r = 0; same && r <= count; ++r) same = row_ptr[r] == outer[r];
    for (int k = 0; same && k < nnz; ++k) same = cols[k] == R.innerIndexPtr()[k];
    int mine = same ? 1 : 0, all = 0;  // a new pattern anywhere: a new matrix everywhere
    MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
    row_ptr.assign(outer, outer + count + 1);
    cols.assign(R.innerIndexPtr(), R.innerIndexPtr() + nnz);
    return all == 1;
  }

  // A matrix of the kept rows of values R's: `rows` of `size` (square) on this process.
  void new_matrix(const RowMat& R, PetscInt rows, PetscInt size) {
    const PetscScalar* values = R.valuePtr();
    OwnedMat M;
    check(MatCreate(PETSC_COMM_WORLD, &M), "matrix");
    check(MatSetSizes(M, rows, rows, size, size), "matrix");
    check(MatSetType(M, MATAIJ), "matrix");
    // (each call is a no-op on the other type: SEQAIJ on one process, MPIAIJ on more)
    check(MatSeqAIJSetPreallocationCSR(M, row_ptr.data(), cols.data(), values), "matrix");
    check(MatMPIAIJSetPreallocationCSR(M, row_ptr.data(), cols.data(), values), "matrix");
    if (symmetric) check(MatSetOption(M, MAT_SYMMETRIC, PETSC_TRUE), "matrix");
    A = std::move(M);
  }

  void new_vectors(Mat op) {
    if (x.p) return;
    check(MatCreateVecs(op, &x, &b), "vector");
    check(VecScatterCreateToAll(x, &to_all, &x_all), "vector");
  }

  // The kept pattern's values from R (this process's rows), the first of them row first_row.
  void refill(const RowMat& R, PetscInt first_row) {
    const PetscScalar* values = R.valuePtr();
    for (PetscInt r = 0; r + 1 < PetscInt(row_ptr.size()); ++r) {
      const PetscInt row = first_row + r, count = row_ptr[r + 1] - row_ptr[r];
      check(MatSetValues(A, 1, &row, count, cols.data() + row_ptr[r], values + row_ptr[r], INSERT_VALUES),
            "matrix");
    }
    check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "matrix");
    check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "matrix");
  }

  // The spline multigrid's setup: the displacement block K + B_A^T W B_A
  // assembled (K + K_coupling, the local unknowns condensed), the
  // constraint rows B, their weights and the active set given to
  // SplineMultigrid, whose shell applies the saddle-point matrix in the
  // constraint form and whose hierarchy is rebuilt on the new block.
  void setup_spline_multigrid(const BlockJacobian& blocks) {
    if (blocks.general)
      throw PetscOptionError(
          "the spline multigrid needs the multipliers apart from the displacements, and this Newton matrix solves "
          "them in one block (friction, ties); leave preconditioner at \"options\"");
    const int n = int(blocks.K.rows());
    m = PetscInt(blocks.B.rows());
    if (!hierarchy->empty() && (*hierarchy)[0].rows() != n)
      throw PetscOptionError(fmt::format("the spline multigrid's finest mesh has {} unknowns, the Newton matrix's "
                                         "displacement block {}: leave preconditioner at \"options\"",
                                         (*hierarchy)[0].rows(), n));
    symmetric = has_symmetric_form(blocks);
    constraint_form = true;
    general = false;
    if (new_size(PetscInt(n + m))) {
      mg.reset();  // (it borrows A)
      ksp = {};
      row_ptr.clear();
      layout = SaddleLayout::of(n, m, first, first + local);
    }
    // this process's rows of the condensed J's displacement block
    W = Eigen::VectorXd::Zero(m);
    std::optional<RowMat> extra;
    if (m > 0) extra = augmentation(blocks, n);
    const RowMat R = condensed_rows(blocks, int(layout.u0), int(layout.u0 + layout.local_u()), n,
                                    extra ? &*extra : nullptr);
    if (keep_rows(R) && A.p && symmetric == ksp_symmetric) {
      refill(R, layout.u0);
    } else {
      mg.reset();
      ksp = {};
      new_matrix(R, layout.local_u(), n);
    }
    ksp_symmetric = symmetric;
    if (!mg || !mg->set_constraints(blocks.B, W, blocks.d)) {
      ksp = {};
      mg.reset();
      // ICC(0) in the natural order: in reverse Cuthill-McKee order (the
      // small-deformation route's choice) the smoother broke down on the
      // O-ring's Newton matrices, and on the 3D Hertz sphere both orders take
      // the same iterations (measured: docs/petsc.md, "Krylov: the spline
      // multigrid on the Newton steps").
      default_option("-u_mg_levels_sub_pc_factor_mat_ordering_type", "natural");
      mg.emplace(A, blocks.B, W, blocks.d, layout, *hierarchy);
    }
    std::vector<char> active(m);
    for (int k = 0; k < m; ++k) active[k] = blocks.s[k] != 0;
    mg->set_active_set(active);
    if (!ksp.p) create_multigrid_solver();
    mg->setup();
    new_vectors(mg->shell());
  }

  // FGMRES (multigrid with a Chebyshev smoother is a fixed operator, a
  // user's inner Krylov -u_ksp_type cg would not be) preconditioned by the
  // spline multigrid's shell.
  void create_multigrid_solver() {
    PetscBool has = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, nullptr, "-pc_type", &has), "options");
    if (has)
      throw PetscOptionError("PETSc option -pc_type: the spline multigrid is the preconditioner (its own options "
                             "start with -u_, e.g. -u_mg_levels_pc_type sor)");
    check(KSPCreate(PETSC_COMM_WORLD, &ksp), "solver");
    mg->attach(ksp);
    default_option("-ksp_type", "fgmres");
    check(KSPSetTolerances(ksp, kTight, 1e-50, PETSC_DEFAULT, 2000), "solver");
    check(KSPSetFromOptions(ksp), "options", true);
    check(KSPSetInitialGuessNonzero(ksp, PETSC_FALSE), "solver");
    check(KSPSetConvergenceTest(ksp, stop_test, this, nullptr), "solver");
  }

  // A Krylov solver's stopping test, on the residual of J itself (its
  // condensed rows as the driver gave them) rather than of the matrix
  // PETSc solves, whose rows differ: the constraint form divides the active
  // rows by s_k, and the augmentation adds B_A^T W (c_A - B_A du) to the
  // displacement rows' residual, W of the size of K.  On the nearly
  // incompressible O-ring (W of the bulk modulus' size) PETSc's own test
  // stopped with J's residual larger than |b|, and every Newton step failed
  // its line search (docs/petsc.md, "The linear backend").
  static PetscErrorCode stop_test(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason* reason, void* self) {
    PetscFunctionBeginUser;
    Impl& I = *static_cast<Impl*>(self);
    *reason = KSP_CONVERGED_ITERATING;
    if (PetscIsInfOrNanReal(rnorm)) {
      *reason = KSP_DIVERGED_NANORINF;
      PetscFunctionReturn(0);
    }
    if (!I.work_t.p) {
      PetscCall(VecDuplicate(I.x, &I.work_t.p));
      PetscCall(VecDuplicate(I.x, &I.work_r.p));
    }
    Vec r = nullptr;
    PetscCall(KSPBuildResidual(ksp, I.work_t, I.work_r, &r));
    PetscCall(VecScatterBegin(I.to_all, r, I.x_all, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(I.to_all, r, I.x_all, INSERT_VALUES, SCATTER_FORWARD));
    const PetscScalar* pr = nullptr;
    PetscCall(VecGetArrayRead(I.x_all, &pr));
    const double norm = I.residual_of_J(pr);
    PetscCall(VecRestoreArrayRead(I.x_all, &pr));
    PetscInt max_it = 0;
    PetscCall(KSPGetTolerances(ksp, nullptr, nullptr, nullptr, &max_it));
    if (norm <= I.stop_at) *reason = KSP_CONVERGED_RTOL;
    else if (it >= max_it) *reason = KSP_DIVERGED_ITS;
    PetscFunctionReturn(0);
  }

  // |J dx - b| from r, the residual of the matrix PETSc solves (whole):
  // an active row's normalised residual q_k = c_k - B_k du is r_k (the
  // constraint form) or r_k / s_k, J's row residual s_k q_k; an inactive
  // row's is r_k (0 in the constraint form: set exactly after the solve);
  // the displacement rows' is r_u - sum over active k of B_k^T W_k q_k.
  double residual_of_J(const double* r) const {
    const int n = int(J->K.rows());
    Eigen::VectorXd ru = Eigen::Map<const Eigen::VectorXd>(r, n);
    double constraints = 0;
    for (int k = 0; k < J->B.rows(); ++k) {
      const double rk = r[n + k];
      if (J->s[k] != 0) {
        const double q = constraint_form ? rk : rk / J->s[k];
        constraints += std::pow(J->s[k] * q, 2);
        if (augmented && W.size() > 0 && W[k] != 0)
          for (RowMat::InnerIterator e(J->B, k); e; ++e) ru[e.col()] -= W[k] * q * e.value();
      } else if (!constraint_form) {
        constraints += rk * rk;
      }
    }
    return std::sqrt(ru.squaredNorm() + constraints);
  }

  // igac's choice, which the options replace: MUMPS, L D L^T on the
  // symmetric form, else LU.
  void create_solver() {
    check(KSPCreate(PETSC_COMM_WORLD, &ksp), "solver");
    ksp_symmetric = symmetric;
    check(KSPSetType(ksp, KSPPREONLY), "solver");
    PC pc = nullptr;
    check(KSPGetPC(ksp, &pc), "solver");
    check(PCSetType(pc, symmetric ? PCCHOLESKY : PCLU), "solver");
    check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "solver");
    // room for delayed pivots: the multiplier rows have no diagonal
    default_option("-mat_mumps_icntl_14", "100");
    check(KSPSetTolerances(ksp, kTight, 1e-50, PETSC_DEFAULT, 2000), "solver");
    check(KSPSetFromOptions(ksp), "options", true);
    KSPType ksp_type = nullptr;
    check(KSPGetType(ksp, &ksp_type), "solver");
    if (ksp_type && std::string(ksp_type) != KSPPREONLY) {
      check(KSPSetInitialGuessNonzero(ksp, PETSC_FALSE), "solver");
      check(KSPSetConvergenceTest(ksp, stop_test, this, nullptr), "solver");
    }
    PCType pc_type = nullptr;
    check(PCGetType(pc, &pc_type), "solver");
    if (pc_type && std::string(pc_type) == PCFIELDSPLIT) {
      if (general)
        throw PetscOptionError(
            "-pc_type fieldsplit: this matrix has no multipliers apart from the displacements (friction and ties "
            "solve them in one block); use a direct solver or a preconditioner of the whole matrix");
      set_fields(pc, A, near_null, SaddleLayout::of(N - m, m, first, first + local), fields);
    }
  }

  // PETSc's reason a factorisation (after a setup) or a solve (`solved`)
  // failed, in words ("" when it did not).  After a setup only the PC's
  // reason counts: the KSP's is the last solve's, which a new matrix
  // replaces (a Krylov solve that diverged once must not fail every setup
  // after it, the step's retries included).
  std::string failure(bool solved) const {
    PC pc = nullptr;
    check(KSPGetPC(ksp, &pc), "solver");
    PCFailedReason pc_reason = PC_NOERROR;
    check(PCGetFailedReason(pc, &pc_reason), "solver");
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    check(KSPGetConvergedReason(ksp, &reason), "solver");
    if (pc_reason != PC_NOERROR) return fmt::format("singular Newton matrix (PETSc: {})", PCFailedReasons[pc_reason]);
    if (solved && reason < 0) return fmt::format("the PETSc linear solve did not converge ({})", KSPConvergedReasons[reason]);
    return {};
  }

  void describe() {
    PC pc = nullptr;
    KSPType ksp_type = nullptr;
    PCType pc_type = nullptr;
    check(KSPGetPC(ksp, &pc), "solver");
    check(KSPGetType(ksp, &ksp_type), "solver");
    check(PCGetType(pc, &pc_type), "solver");
    method = fmt::format("{} + {}", ksp_type ? ksp_type : "?",
                         mg ? fmt::format("spline multigrid ({} levels)", mg->levels()) : pc_type ? pc_type : "?");
    if (pc_type && (std::string(pc_type) == PCLU || std::string(pc_type) == PCCHOLESKY)) {
      MatSolverType st = nullptr;
      if (!PCFactorGetMatSolverType(pc, &st) && st) method += fmt::format(" ({})", st);
    }
  }
};

PetscNewtonSolver::PetscNewtonSolver(Eigen::MatrixXd near_null, std::optional<std::vector<RowSparse>> spline_hierarchy)
    : impl_(std::make_unique<Impl>()) {
  if (!PetscSession::active()) throw std::logic_error("PetscNewtonSolver needs a PetscSession");
  impl_->near_null = std::move(near_null);
  impl_->hierarchy = std::move(spline_hierarchy);
  char pc_type[64] = "";
  PetscBool given = PETSC_FALSE;
  check(PetscOptionsGetString(nullptr, nullptr, "-pc_type", pc_type, sizeof pc_type, &given), "options", true);
  impl_->augmented = impl_->hierarchy || (given && std::string(pc_type) != PCLU && std::string(pc_type) != PCCHOLESKY);
}
PetscNewtonSolver::~PetscNewtonSolver() = default;

bool PetscNewtonSolver::setup(const BlockJacobian& J) {
  auto& I = *impl_;
  const Stopwatch clock;
  ++stats_.setups;
  why_.clear();
  I.J = &J;
  if (J.has_mixed_rows()) {  // (friction's slip rows) MUMPS factorises the whole: the rows inside it
    I.one_block = as_one_block(J);
    I.J = &I.one_block;
  }
  if (I.hierarchy) {
    I.setup_spline_multigrid(*I.J);  // (the hierarchy's setup counted as the matrix's)
    stats_.schur_s += clock.seconds();
    why_ = I.mg->setup_failure();
    return why_.empty();
  }
  RowMat R;
  if (I.take_rows(*I.J, R) && I.A.p) {
    I.refill(R, I.first);
  } else {
    I.new_matrix(R, I.local, I.N);
    I.new_vectors(I.A);
  }
  stats_.schur_s += clock.seconds();  // (here: the matrix handed to PETSc)
  const Stopwatch factor_clock;
  if (!I.ksp.p) I.create_solver();
  check(KSPSetOperators(I.ksp, I.A, I.A), "solver");
  check(KSPSetUp(I.ksp), "solver setup", !I.solved_once);
  stats_.factorize_s += factor_clock.seconds();
  why_ = I.failure(false);
  return why_.empty();
}

bool PetscNewtonSolver::solve(const Eigen::VectorXd& b_whole, Eigen::VectorXd& x, double tolerance) {
  auto& I = *impl_;
  const Stopwatch clock;
  ++stats_.solves;
  const CondensedRhs rhs = condense_rhs(*I.J, b_whole);
  Eigen::VectorXd b = rhs.b;
  if (I.constraint_form) {  // the symmetric form's right-hand side (Impl::has_symmetric_form)
    const BlockJacobian& J = *I.J;
    const int n = int(J.K.rows());
    for (int k = 0; k < J.B.rows(); ++k) {
      if (J.s[k] != 0) {
        b[n + k] /= J.s[k];
      } else {
        // dl_k = b_k / d_k exactly (set after the solve): its row asks
        // nothing of the solver, whose stopping test (|b - A x| / |b| for
        // a Krylov solver) it would otherwise dominate
        const double dl = rhs.b[n + k] / J.d[k];
        for (RowMat::InnerIterator it(J.B, k); it; ++it) b[it.col()] -= it.value() * dl;
        b[n + k] = 0;
      }
    }
  }
  if (I.augmented && I.W.size() > 0) {  // the augmentation's right-hand side: B_A^T W c_A (Impl::augmentation)
    const BlockJacobian& J = *I.J;
    const int n = int(J.K.rows());
    for (int k = 0; k < J.B.rows(); ++k) {
      if (I.W[k] == 0) continue;
      const double c = rhs.b[n + k] / J.s[k];
      for (RowMat::InnerIterator it(J.B, k); it; ++it) b[it.col()] += I.W[k] * c * it.value();
    }
  }
  PetscScalar* pb = nullptr;
  check(VecGetArray(I.b, &pb), "vector");
  std::copy(b.data() + I.first, b.data() + I.first + I.local, pb);
  check(VecRestoreArray(I.b, &pb), "vector");
  check(KSPSetTolerances(I.ksp, tolerance > 0 ? tolerance : kTight, 1e-50, PETSC_DEFAULT, 2000), "solver");
  I.stop_at = (tolerance > 0 ? tolerance : kTight) * rhs.b.norm();
  check(KSPSolve(I.ksp, I.b, I.x), "solve", !I.solved_once);
  if (!I.solved_once) refuse_unused_options();
  I.solved_once = true;
  I.describe();  // the method of this solve's KSP (a new one after a change of form: LU after L D L^T)
  PetscInt iterations = 0;
  check(KSPGetIterationNumber(I.ksp, &iterations), "solver");
  stats_.krylov_iterations += int(iterations);
  I.iterations.push_back(int(iterations));
  why_ = I.failure(true);
  check(VecScatterBegin(I.to_all, I.x, I.x_all, INSERT_VALUES, SCATTER_FORWARD), "vector");
  check(VecScatterEnd(I.to_all, I.x, I.x_all, INSERT_VALUES, SCATTER_FORWARD), "vector");
  const PetscScalar* px = nullptr;
  check(VecGetArrayRead(I.x_all, &px), "vector");
  x = Eigen::Map<const Eigen::VectorXd>(px, I.N);
  check(VecRestoreArrayRead(I.x_all, &px), "vector");
  if (I.constraint_form) {  // an inactive multiplier's row is d_k dl_k = b_k: exactly, not through MUMPS' scaling
    const BlockJacobian& J = *I.J;
    const int n = int(J.K.rows());
    for (int k = 0; k < J.B.rows(); ++k)
      if (J.s[k] == 0) x[n + k] = rhs.b[n + k] / J.d[k];
  }
  recover_local(*I.J, rhs, x);
  stats_.solve_s += clock.seconds();
  if (why_.empty() && !x.allFinite()) why_ = "singular Newton matrix (the PETSc solution is not finite)";
  return why_.empty();
}

LinearBackendReport PetscNewtonSolver::report() const {
  double mine = peak_resident_gib(), all = mine;
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  const bool direct = impl_->method.starts_with("preonly");
  return {.type = "petsc", .method = impl_->method, .iterations = direct ? std::vector<int>{} : impl_->iterations,
          .ranks = PetscSession::size(), .peak_resident_all_ranks_gib = all};
}

}  // namespace igac
