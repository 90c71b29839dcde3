// SPDX-License-Identifier: BSD-3-Clause
#include "engine/cholesky.hpp"
#include "engine/dense_kernels.hpp"

#include "engine/condition_estimate.hpp"

#include <algorithm>
#include <cholmod.h>
#include <cstdlib>
#include <dlfcn.h>
#include <omp.h>
#include <fmt/format.h>
#include <stdexcept>

#include "engine/stopwatch.hpp"

namespace igac {
namespace {
// A CHOLMOD view (no copy) of the lower triangle of a compressed Eigen matrix.
cholmod_sparse view_lower(const Eigen::SparseMatrix<double>& A) {
  cholmod_sparse s{};
  s.nrow = A.rows();
  s.ncol = A.cols();
  s.nzmax = A.nonZeros();
  s.p = const_cast<int*>(A.outerIndexPtr());
  s.i = const_cast<int*>(A.innerIndexPtr());
  s.x = const_cast<double*>(A.valuePtr());
  s.stype = -1;
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

// OpenBLAS's threads (the pthread build Debian installs) pay only on large
// dense blocks: below ~1e10 flops a factorisation is as fast on one thread
// (2D at 34k dofs, p = 3: 0.45 s either way), and when the other core is
// busy two threads cost 10-20x (their barriers wait for a time slice:
// hertz2d 0.008 s -> 0.15 s).  Above, two threads take 3D factorisations
// down by 25-30 %.  Found through dlsym, so any other BLAS works unchanged;
// OPENBLAS_NUM_THREADS or OMP_NUM_THREADS in the environment win.
class BlasThreads {
 public:
  static constexpr double kThreadedFlops = 1e10;
  static int for_flops(double flops) {
    const Api& a = api();
    if (!a.set || !a.get || a.user_chose) return 0;  // 0: leave OpenBLAS alone
    return flops < kThreadedFlops ? 1 : a.initial;
  }
  static void set(int n) {
    if (n > 0) api().set(n);
  }
  static int current() { return api().get ? api().get() : 0; }
  // OpenBLAS built on OpenMP (libopenblas0-openmp) runs on libgomp's own
  // workers: nothing spins against it, and serialising OpenMP would
  // serialise it too.
  static bool uses_openmp() { return api().parallel == 2; }

 private:
  struct Api {
    void (*set)(int) = nullptr;
    int (*get)() = nullptr;
    int initial = 1;
    int parallel = 0;  // openblas_get_parallel(): 0 sequential, 1 pthreads, 2 OpenMP
    bool user_chose = false;
  };
  static const Api& api() {
    static const Api a = [] {
      Api r;
      r.set = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
      r.get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
      r.initial = r.get ? r.get() : 1;
      if (auto parallel = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_parallel")))
        r.parallel = parallel();
      r.user_chose = std::getenv("OPENBLAS_NUM_THREADS") || std::getenv("OMP_NUM_THREADS");
      return r;
    }();
    return a;
  }
};

// CHOLMOD's own OpenMP loops (num_threads(4), compiled in, per supernode)
// leave libgomp's idle workers spinning on the other core for some
// milliseconds after each loop, exactly when OpenBLAS wants that core for
// the supernode's dense kernels: measured 10-40x slower factorisations in
// 2D (0.014 s -> 0.13-0.58 s at 2.5k dofs) and 2.5x in 3D (hertz3d 7.7 s ->
// 2.5 s).  Inside a CHOLMOD call every OpenMP region runs on one thread;
// the cores go to OpenBLAS's threads, as many as the work pays for
// (BlasThreads).  Our own threaded loops (assembly) are untouched.
class BlasOwnsTheCores {
 public:
  explicit BlasOwnsTheCores(double flops = 0)
      : levels_(omp_get_max_active_levels()), threads_(BlasThreads::current()) {
    if (!BlasThreads::uses_openmp()) omp_set_max_active_levels(0);
    BlasThreads::set(BlasThreads::for_flops(flops));
  }
  ~BlasOwnsTheCores() {
    omp_set_max_active_levels(levels_);
    BlasThreads::set(threads_);
  }
  BlasOwnsTheCores(const BlasOwnsTheCores&) = delete;
  BlasOwnsTheCores& operator=(const BlasOwnsTheCores&) = delete;

 private:
  int levels_, threads_;
};
}  // namespace

struct SparseCholesky::Impl {
  cholmod_common c;
  cholmod_factor* L = nullptr;
  std::vector<int> position;  // position[original equation] in the factor
  std::vector<int> super_of;  // supernode of each factor column
  std::vector<int> parent;    // supernodal elimination tree (-1: a root)
  double flops = 0;           // of one numeric factorisation with the kept ordering
  Impl() {
    cholmod_start(&c);
    c.print = 0;  // no "CHOLMOD warning" lines (CHOLMOD prints them on stdout, in a run's summary):
  }               // callers read c.status; an indefinite matrix is what the Newton path falls back from
  ~Impl() {
    if (L) cholmod_free_factor(&L, &c);
    cholmod_finish(&c);
  }
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;
bool SparseCholesky::analyzed() const { return impl_->L != nullptr; }
double SparseCholesky::factor_nonzeros() const {
  return impl_->L ? double(impl_->L->is_super ? impl_->L->xsize : impl_->L->nzmax) : 0.0;
}

void SparseCholesky::analyze(const Eigen::SparseMatrix<double>& A_in, const std::vector<int>& last) {
  const Stopwatch clock;
  Eigen::SparseMatrix<double> A = A_in;
  A.makeCompressed();
  cholmod_sparse a = view_lower(A);
  auto& I = *impl_;
  const BlasOwnsTheCores blas;
  if (I.L) cholmod_free_factor(&I.L, &I.c);
  I.c.supernodal = CHOLMOD_SUPERNODAL;
  if (last.empty()) {
    I.c.nmethods = 0;  // CHOLMOD's default: AMD, and METIS when AMD fills badly
    I.L = cholmod_analyze(&a, &I.c);
  } else {
    // Constrained AMD first; when its flop count per factor entry shows
    // deep fill (3D), also nested dissection (METIS) with the constrained
    // equations moved last, and keep the cheaper factorisation.
    const int n = int(A.rows());
    std::vector<int> cmember(n, 0), perm(n);
    for (int e : last) cmember[e] = 1;
    I.c.nmethods = 1;
    I.c.method[0].ordering = CHOLMOD_GIVEN;
    if (!cholmod_camd(&a, nullptr, 0, cmember.data(), perm.data(), &I.c))
      throw std::runtime_error("CHOLMOD: constrained ordering failed");
    I.L = cholmod_analyze_p(&a, perm.data(), nullptr, 0, &I.c);
    constexpr double kDeepFill = 1000.0;  // flops per factor entry above which METIS pays (CHOLMOD uses 500)
    if (I.L && I.c.fl > kDeepFill * I.c.lnz && cholmod_metis(&a, nullptr, 0, 1, perm.data(), &I.c)) {
      const double fl_amd = I.c.fl;
      std::stable_partition(perm.begin(), perm.end(), [&](int e) { return cmember[e] == 0; });
      cholmod_factor* L2 = cholmod_analyze_p(&a, perm.data(), nullptr, 0, &I.c);
      if (L2 && I.c.fl < fl_amd) {
        cholmod_free_factor(&I.L, &I.c);
        I.L = L2;
      } else if (L2) {
        cholmod_free_factor(&L2, &I.c);
        I.c.fl = fl_amd;
      }
    }
  }
  if (!I.L) throw std::runtime_error("CHOLMOD: symbolic analysis failed (out of memory?)");
  I.flops = I.c.fl;
  const int n = int(A.rows());
  const int* P = static_cast<const int*>(I.L->Perm);
  I.position.assign(n, 0);
  for (int k = 0; k < n; ++k) I.position[P[k]] = k;
  I.c.nmethods = 0;
  // Supernodal elimination tree: the parent of a supernode holds its first
  // off-diagonal row.
  const int* super = static_cast<const int*>(I.L->super);
  const int* pi = static_cast<const int*>(I.L->pi);
  const int* ls = static_cast<const int*>(I.L->s);
  const int ns = int(I.L->nsuper);
  I.super_of.assign(n, 0);
  I.parent.assign(ns, -1);
  for (int k = 0; k < ns; ++k)
    for (int j = super[k]; j < super[k + 1]; ++j) I.super_of[j] = k;
  for (int k = 0; k < ns; ++k) {
    const int nscol = super[k + 1] - super[k];
    int first = n;
    for (int r = pi[k] + nscol; r < pi[k + 1]; ++r) first = std::min(first, ls[r]);
    if (first < n) I.parent[k] = I.super_of[first];
  }
  analyze_s_ = clock.seconds();
}

void SparseCholesky::factorize(const Eigen::SparseMatrix<double>& A_in) {
  if (!analyzed()) analyze(A_in);
  const Stopwatch clock;
  Eigen::SparseMatrix<double> A = A_in;
  A.makeCompressed();
  cholmod_sparse a = view_lower(A);
  auto& I = *impl_;
  const BlasOwnsTheCores blas(I.flops);
  cholmod_factorize(&a, I.L, &I.c);
  indefinite_at_ = -1;
  if (I.c.status == CHOLMOD_NOT_POSDEF || I.L->minor < I.L->n) {
    const int* perm = static_cast<const int*>(I.L->Perm);
    if (I.L->minor < I.L->n) indefinite_at_ = perm ? perm[I.L->minor] : int(I.L->minor);
    throw std::runtime_error(
        "the stiffness matrix is not positive definite: the body can move rigidly "
        "(add Dirichlet conditions or contact) or the data are singular");
  }
  if (I.c.status < 0) throw std::runtime_error(fmt::format("CHOLMOD factorisation failed (status {})", I.c.status));
  norm1_ = norm1(A);
  factorize_s_ = clock.seconds();
}

double SparseCholesky::condition_estimate() const {
  if (!impl_->L) throw std::logic_error("SparseCholesky::condition_estimate before factorize");
  const VectorSolve solve = [this](const Eigen::VectorXd& b) -> Eigen::VectorXd { return this->solve(b); };
  return norm1_ * inverse_norm1_estimate(size(), solve, solve);  // A = A^T
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
  auto& I = *impl_;
  if (!I.L) throw std::logic_error("SparseCholesky::solve before factorize");
  cholmod_dense b{};
  b.nrow = B.rows();
  b.ncol = B.cols();
  b.nzmax = B.size();
  b.d = B.rows();
  b.x = const_cast<double*>(B.data());
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  const BlasOwnsTheCores blas(4.0 * factor_nonzeros() * double(B.cols()));  // forward and backward
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, I.L, &b, &I.c);
  if (!x) throw std::runtime_error("CHOLMOD solve failed");
  Eigen::MatrixXd X = Eigen::Map<Eigen::MatrixXd>(static_cast<double*>(x->x), B.rows(), B.cols());
  cholmod_free_dense(&x, &I.c);
  return X;
}

int SparseCholesky::position(int equation) const { return impl_->position[equation]; }
int SparseCholesky::size() const { return impl_->L ? int(impl_->L->n) : 0; }

SparseCholesky::Reach SparseCholesky::reach(const std::vector<int>& equations) const {
  const auto& I = *impl_;
  if (!I.L) throw std::logic_error("SparseCholesky::reach before analyze");
  std::vector<char> in(I.parent.size(), 0);
  Reach R;
  for (int e : equations)
    for (int k = I.super_of[I.position[e]]; k >= 0 && !in[k]; k = I.parent[k]) {
      in[k] = 1;
      R.supernodes.push_back(k);
    }
  std::sort(R.supernodes.begin(), R.supernodes.end());
  const int* super = static_cast<const int*>(I.L->super);
  for (int k : R.supernodes)
    for (int j = super[k]; j < super[k + 1]; ++j) R.rows.push_back(j);
  return R;
}

namespace {
// One supernode of the numeric factor: its columns k1..k2-1, its rows
// (the first nscol are the columns themselves) and the dense nsrow x nscol
// block, column major.
struct Supernode {
  int k1, nscol, nsrow;
  const int* rows;
  const double* x;
};
Supernode supernode(const cholmod_factor* L, int k) {
  const int* super = static_cast<const int*>(L->super);
  const int* pi = static_cast<const int*>(L->pi);
  const int* px = static_cast<const int*>(L->px);
  return {super[k], super[k + 1] - super[k], pi[k + 1] - pi[k], static_cast<const int*>(L->s) + pi[k],
          static_cast<const double*>(L->x) + px[k]};
}
using Block = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
}  // namespace

namespace {
// Y = L^{-1} C on a reach, C given as dense columns on the reach's rows
// (`local` rows), each zero above start[j] and the starts ascending: a
// supernode updates only the prefix of the columns that have started, so
// the zeros above each column's start are never multiplied.
void forward_started(const cholmod_factor* L, const SparseCholesky::Reach& R, const std::vector<int>& local,
                     const std::vector<int>& start, Eigen::MatrixXd& Y) {
  // Within a supernode (the trailing one of a contact face holds thousands
  // of rows) the started columns go in chunks, each from the chunk's first
  // start down: the triangle's zeros inside the supernode are skipped too.
  constexpr int kChunk = 256;
  Eigen::MatrixXd W;
  for (int k : R.supernodes) {
    const Supernode sn = supernode(L, k);
    const Block Lk(sn.x, sn.nsrow, sn.nscol, Eigen::OuterStride<>(sn.nsrow));
    const int first = local[sn.k1];
    const int started = int(std::upper_bound(start.begin(), start.end(), first + sn.nscol - 1) - start.begin());
    const int below = sn.nsrow - sn.nscol;
    for (int c0 = 0; c0 < started; c0 += kChunk) {
      const int width = std::min(kChunk, started - c0);
      const int skip = std::max(0, start[c0] - first);  // rows of this supernode above the chunk's columns
      auto Xk = Y.block(first + skip, c0, sn.nscol - skip, width);
      dense::lower_solve_in_place(Lk.block(skip, skip, sn.nscol - skip, sn.nscol - skip), Xk);
      if (below == 0) continue;
      W.resize(below, width);
      dense::gemm(1.0, Lk.block(sn.nscol, skip, below, sn.nscol - skip), false, Xk, false, 0.0, W);
      for (int r = 0; r < below; ++r) Y.row(local[sn.rows[sn.nscol + r]]).segment(c0, width) -= W.row(r);
    }
  }
}
}  // namespace

SparseCholesky::ColumnsByStart SparseCholesky::forward_by_start(const Reach& R,
                                                                const Eigen::SparseMatrix<double>& C) const {
  const auto& I = *impl_;
  if (!I.L || !I.L->x) throw std::logic_error("SparseCholesky::forward before factorize");
  const int nz = int(R.rows.size()), nc = int(C.cols());
  std::vector<int> local(I.L->n, -1);
  for (int i = 0; i < nz; ++i) local[R.rows[i]] = i;
  // A column of L^{-1} P C is zero above its first nonzero (the reach rows
  // ascend with the factor's positions).  The columns are solved in the
  // order of that row, each from it down (forward_started).
  std::vector<int> first(nc, nz);
  for (int j = 0; j < C.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(C, j); it; ++it) {
      const int l = local[I.position[it.row()]];
      if (l < 0) throw std::logic_error("SparseCholesky::forward: a column reaches outside the reach");
      first[j] = std::min(first[j], l);
    }
  ColumnsByStart out;
  out.order.resize(nc);
  for (int j = 0; j < nc; ++j) out.order[j] = j;
  std::stable_sort(out.order.begin(), out.order.end(), [&](int a, int b) { return first[a] < first[b]; });
  out.start.resize(nc);
  std::vector<int> column_of(nc);
  for (int i = 0; i < nc; ++i) {
    out.start[i] = first[out.order[i]];
    column_of[out.order[i]] = i;
  }
  out.Y = Eigen::MatrixXd::Zero(nz, nc);
  for (int j = 0; j < C.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(C, j); it; ++it)
      out.Y(local[I.position[it.row()]], column_of[j]) = it.value();
  forward_started(I.L, R, local, out.start, out.Y);
  return out;
}

Eigen::MatrixXd SparseCholesky::forward(const Reach& R, const Eigen::SparseMatrix<double>& C) const {
  ColumnsByStart sorted = forward_by_start(R, C);
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic> back(Eigen::Index(sorted.order.size()));
  for (std::size_t i = 0; i < sorted.order.size(); ++i) back.indices()[sorted.order[i]] = int(i);
  sorted.Y = sorted.Y * back;  // column j is C's column j again
  return std::move(sorted.Y);
}

Eigen::VectorXd SparseCholesky::backward(const Reach& R, const Eigen::VectorXd& y) const {
  const auto& I = *impl_;
  if (!I.L || !I.L->x) throw std::logic_error("SparseCholesky::backward before factorize");
  std::vector<int> local(I.L->n, -1);
  for (size_t i = 0; i < R.rows.size(); ++i) local[R.rows[i]] = int(i);
  Eigen::VectorXd x = y, xb;
  for (auto k = R.supernodes.rbegin(); k != R.supernodes.rend(); ++k) {
    const Supernode sn = supernode(I.L, *k);
    const Block Lk(sn.x, sn.nsrow, sn.nscol, Eigen::OuterStride<>(sn.nsrow));
    auto Xk = x.segment(local[sn.k1], sn.nscol);
    const int below = sn.nsrow - sn.nscol;
    if (below > 0) {
      xb.resize(below);
      for (int r = 0; r < below; ++r) xb[r] = x[local[sn.rows[sn.nscol + r]]];
      Xk.noalias() -= Lk.bottomRows(below).transpose() * xb;
    }
    Lk.topRows(sn.nscol).triangularView<Eigen::Lower>().transpose().solveInPlace(Xk);
  }
  return x;
}

namespace {
Eigen::VectorXd cholmod_system(int sys, cholmod_factor* L, const Eigen::VectorXd& b, cholmod_common* c) {
  cholmod_dense d{};
  d.nrow = b.size();
  d.ncol = 1;
  d.nzmax = b.size();
  d.d = b.size();
  d.x = const_cast<double*>(b.data());
  d.xtype = CHOLMOD_REAL;
  d.dtype = CHOLMOD_DOUBLE;
  const BlasOwnsTheCores blas;
  cholmod_dense* x = cholmod_solve(sys, L, &d, c);
  if (!x) throw std::runtime_error("CHOLMOD solve failed");
  Eigen::VectorXd out = Eigen::Map<Eigen::VectorXd>(static_cast<double*>(x->x), b.size());
  cholmod_free_dense(&x, c);
  return out;
}
}  // namespace

Eigen::VectorXd SparseCholesky::forward_full(const Eigen::VectorXd& b) const {
  auto& I = *impl_;
  if (!I.L || !I.L->x) throw std::logic_error("SparseCholesky::forward_full before factorize");
  return cholmod_system(CHOLMOD_L, I.L, cholmod_system(CHOLMOD_P, I.L, b, &I.c), &I.c);
}

Eigen::VectorXd SparseCholesky::backward_full(const Eigen::VectorXd& y) const {
  auto& I = *impl_;
  if (!I.L || !I.L->x) throw std::logic_error("SparseCholesky::backward_full before factorize");
  return cholmod_system(CHOLMOD_Pt, I.L, cholmod_system(CHOLMOD_Lt, I.L, y, &I.c), &I.c);
}

Eigen::VectorXd SparseCholesky::pivots() const {
  const auto& I = *impl_;
  if (!I.L || !I.L->x) throw std::logic_error("SparseCholesky::pivots before factorize");
  const int* P = static_cast<const int*>(I.L->Perm);
  Eigen::VectorXd out(Eigen::Index(I.L->n));
  for (int k = 0; k < int(I.L->nsuper); ++k) {
    const Supernode s = supernode(I.L, k);
    for (int j = 0; j < s.nscol; ++j) out[P[s.k1 + j]] = s.x[j * s.nsrow + j] * s.x[j * s.nsrow + j];
  }
  return out;
}

}  // namespace igac
