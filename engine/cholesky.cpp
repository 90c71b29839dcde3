#include "engine/cholesky.hpp"

#include <algorithm>
#include <chrono>
#include <cholmod.h>
#include <fmt/format.h>
#include <stdexcept>

namespace igac {
namespace {
double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

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
}  // namespace

struct SparseCholesky::Impl {
  cholmod_common c;
  cholmod_factor* L = nullptr;
  Eigen::MatrixXd L_TT;       // dense trailing block of the factor
  std::vector<int> position;  // position[original equation] in the factor
  int t0 = 0;                 // first trailing position
  Impl() { cholmod_start(&c); }
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
  const auto t0 = std::chrono::steady_clock::now();
  Eigen::SparseMatrix<double> A = A_in;
  A.makeCompressed();
  cholmod_sparse a = view_lower(A);
  auto& I = *impl_;
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
      }
    }
  }
  if (!I.L) throw std::runtime_error("CHOLMOD: symbolic analysis failed (out of memory?)");
  const int n = int(A.rows());
  const int* P = static_cast<const int*>(I.L->Perm);
  I.position.assign(n, 0);
  for (int k = 0; k < n; ++k) I.position[P[k]] = k;
  I.t0 = n;
  for (int e : last) I.t0 = std::min(I.t0, I.position[e]);
  trailing_size_ = last.empty() ? 0 : n - I.t0;
  I.c.nmethods = 0;
  analyze_s_ = since(t0);
}

void SparseCholesky::factorize(const Eigen::SparseMatrix<double>& A_in) {
  if (!analyzed()) analyze(A_in);
  const auto t0 = std::chrono::steady_clock::now();
  Eigen::SparseMatrix<double> A = A_in;
  A.makeCompressed();
  cholmod_sparse a = view_lower(A);
  auto& I = *impl_;
  cholmod_factorize(&a, I.L, &I.c);
  if (I.c.status == CHOLMOD_NOT_POSDEF || I.L->minor < I.L->n)
    throw std::runtime_error(
        "the stiffness matrix is not positive definite: the body can move rigidly "
        "(add Dirichlet conditions or contact) or the data are singular");
  if (I.c.status < 0) throw std::runtime_error(fmt::format("CHOLMOD factorisation failed (status {})", I.c.status));
  // Trailing block of the supernodal factor, dense.
  const int n = int(I.L->n), t = n - I.t0;
  I.L_TT.setZero(t, t);
  if (t > 0) {
    const int* super = static_cast<const int*>(I.L->super);
    const int* pi = static_cast<const int*>(I.L->pi);
    const int* px = static_cast<const int*>(I.L->px);
    const int* s = static_cast<const int*>(I.L->s);
    const double* x = static_cast<const double*>(I.L->x);
    for (size_t k = 0; k < I.L->nsuper; ++k) {
      const int k1 = super[k], k2 = super[k + 1];
      if (k2 <= I.t0) continue;
      const int nsrow = pi[k + 1] - pi[k];
      for (int j = std::max(k1, I.t0); j < k2; ++j)
        for (int r = j - k1; r < nsrow; ++r) {
          const int row = s[pi[k] + r];
          I.L_TT(row - I.t0, j - I.t0) = x[px[k] + r + (j - k1) * nsrow];
        }
    }
  }
  factorize_s_ = since(t0);
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
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, I.L, &b, &I.c);
  if (!x) throw std::runtime_error("CHOLMOD solve failed");
  Eigen::MatrixXd X = Eigen::Map<Eigen::MatrixXd>(static_cast<double*>(x->x), B.rows(), B.cols());
  cholmod_free_dense(&x, &I.c);
  return X;
}

Eigen::MatrixXd SparseCholesky::half_solve_trailing(const Eigen::SparseMatrix<double>& C) const {
  auto& I = *impl_;
  const int t = int(I.L_TT.rows());
  Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(t, C.cols());
  for (int j = 0; j < C.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(C, j); it; ++it) {
      const int pos = I.position[it.row()];
      if (pos < I.t0) throw std::logic_error("half_solve_trailing: a column reaches outside the trailing block");
      Y(pos - I.t0, j) = it.value();
    }
  I.L_TT.triangularView<Eigen::Lower>().solveInPlace(Y);
  return Y;
}

}  // namespace igac
