// SPDX-License-Identifier: BSD-3-Clause
#include "engine/dense_kernels.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

extern "C" {
void dgemm_(const char* ta, const char* tb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc);
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* beta, double* c, const int* ldc);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb);
void dgetrf_(const int* m, const int* n, double* a, const int* lda, int* ipiv, int* info);
void dgetrs_(const char* trans, const int* n, const int* nrhs, const double* a, const int* lda, const int* ipiv,
             double* b, const int* ldb, int* info);
}

namespace igac::dense {

namespace {
int ld(Eigen::Index outer_stride, Eigen::Index rows) { return int(std::max<Eigen::Index>({outer_stride, rows, 1})); }
}  // namespace

void gemm(double alpha, const ConstBlock& A, bool transpose_A, const ConstBlock& B, bool transpose_B, double beta,
          Block C) {
  const int m = int(C.rows()), n = int(C.cols()), k = int(transpose_A ? A.rows() : A.cols());
  if ((transpose_A ? A.cols() : A.rows()) != m || (transpose_B ? B.rows() : B.cols()) != n ||
      (transpose_B ? B.cols() : B.rows()) != k)
    throw std::invalid_argument("dense::gemm: sizes do not match");
  if (m == 0 || n == 0) return;
  if (k == 0) {
    C *= beta;
    return;
  }
  const char ta = transpose_A ? 'T' : 'N', tb = transpose_B ? 'T' : 'N';
  const int lda = ld(A.outerStride(), A.rows()), ldb = ld(B.outerStride(), B.rows()), ldc = ld(C.outerStride(), C.rows());
  dgemm_(&ta, &tb, &m, &n, &k, &alpha, A.data(), &lda, B.data(), &ldb, &beta, C.data(), &ldc);
}

Eigen::MatrixXd gram(const ConstBlock& Y, const std::vector<int>& start) {
  const int n = int(Y.cols()), rows = int(Y.rows());
  if (int(start.size()) != n || !std::is_sorted(start.begin(), start.end()))
    throw std::invalid_argument("dense::gram: the column starts are not one ascending list per column");
  // Blocks of columns; S(I, J) for I before J needs the rows from J's first
  // start down (every column of I or J is zero above it).
  constexpr int kBlock = 256;
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, n);
  for (int j0 = 0; j0 < n; j0 += kBlock) {
    const int nj = std::min(kBlock, n - j0), r0 = std::min(start[j0], rows), k = rows - r0;
    if (k == 0) continue;
    const auto YJ = Y.block(r0, j0, k, nj);
    const double one = 1, zero = 0;
    const int lda = ld(Y.outerStride(), Y.rows()), ldc = ld(S.outerStride(), S.rows());
    dsyrk_("L", "T", &nj, &k, &one, YJ.data(), &lda, &zero, S.data() + j0 + Eigen::Index(j0) * ldc, &ldc);
    if (j0 > 0) gemm(1.0, Y.block(r0, j0, k, nj), true, Y.block(r0, 0, k, j0), false, 0.0, S.block(j0, 0, nj, j0));
  }
  S.triangularView<Eigen::StrictlyUpper>() = S.transpose();
  return S;
}

Eigen::MatrixXd gram(const ConstBlock& Y) { return gram(Y, std::vector<int>(std::size_t(Y.cols()), 0)); }

void lower_solve_in_place(const ConstBlock& L, Block X) {
  const int m = int(X.rows()), n = int(X.cols());
  if (L.rows() != m || L.cols() != m) throw std::invalid_argument("dense::lower_solve_in_place: sizes do not match");
  if (m == 0 || n == 0) return;
  const double one = 1;
  const int lda = ld(L.outerStride(), L.rows()), ldb = ld(X.outerStride(), X.rows());
  dtrsm_("L", "L", "N", "N", &m, &n, &one, L.data(), &lda, X.data(), &ldb);
}

void Lu::compute(const Eigen::Ref<const Eigen::MatrixXd>& A) {
  if (A.rows() != A.cols()) throw std::invalid_argument("dense::Lu: not square");
  lu_ = A;
  const int n = int(A.rows());
  pivots_.assign(std::size_t(n), 0);
  singular_ = false;
  if (n == 0) return;
  int info = 0;
  dgetrf_(&n, &n, lu_.data(), &n, pivots_.data(), &info);
  const Eigen::VectorXd d = lu_.diagonal().cwiseAbs();
  singular_ = info < 0 || !d.allFinite() ||
              !(d.minCoeff() > Eigen::NumTraits<double>::epsilon() * double(n) * d.maxCoeff());
}

Eigen::VectorXd Lu::solve(const Eigen::VectorXd& b) const {
  const int n = int(lu_.rows()), one = 1;
  Eigen::VectorXd x = b;
  if (n == 0) return x;
  int info = 0;
  dgetrs_("N", &n, &one, lu_.data(), &n, pivots_.data(), x.data(), &n, &info);
  return x;
}

}  // namespace igac::dense
