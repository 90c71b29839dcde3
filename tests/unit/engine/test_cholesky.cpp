// SPDX-License-Identifier: BSD-3-Clause
// engine/cholesky around its CHOLMOD calls: during a call OpenMP regions are
// serialised and OpenBLAS gets as many threads as the work pays for; after
// it both are as they were (the assembly's threads must not stay off), and
// CHOLMOD never prints (its warnings go to stdout, where a run's summary is
// read by people and scripts; an indefinite matrix is an exception the
// caller handles, e.g. the Newton path's fallback, not a warning line).
// The factor's pivots: their product is det A at round-off, and a matrix
// nearly singular along some motion has one pivot far below its diagonal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <dlfcn.h>
#include <omp.h>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "engine/cholesky.hpp"

namespace igac {
namespace {

// The 1D Laplacian of size n (SPD), shifted by `shift` on the diagonal
// (shift < -4 sin^2(pi/(2(n+1))) makes it indefinite).
Eigen::SparseMatrix<double> laplacian(int n, double shift = 0) {
  Eigen::SparseMatrix<double> A(n, n);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 + shift);
    if (i > 0) t.emplace_back(i, i - 1, -1.0), t.emplace_back(i - 1, i, -1.0);
  }
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

int openblas_threads() {
  auto get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  return get ? get() : -1;  // -1: not OpenBLAS
}

TEST(CholeskyThreads, OpenMpAndBlasSettingsAreRestoredAfterEveryCall) {
  const int levels = omp_get_max_active_levels(), blas = openblas_threads();
  ASSERT_GE(levels, 1) << "OpenMP regions must be allowed outside CHOLMOD calls";
  const Eigen::SparseMatrix<double> A = laplacian(500);
  SparseCholesky chol;
  chol.analyze(A);
  EXPECT_EQ(omp_get_max_active_levels(), levels);
  chol.factorize(A);
  EXPECT_EQ(omp_get_max_active_levels(), levels);
  EXPECT_EQ(openblas_threads(), blas);
  const Eigen::MatrixXd x = chol.solve(Eigen::MatrixXd::Ones(500, 3));
  EXPECT_EQ(omp_get_max_active_levels(), levels);
  EXPECT_EQ(openblas_threads(), blas);
  EXPECT_LE((A * x - Eigen::MatrixXd::Ones(500, 3)).cwiseAbs().maxCoeff(), 1e-9);  // round-off of cond ~ 1e5
  chol.backward_full(chol.forward_full(Eigen::VectorXd::Ones(500)));
  EXPECT_EQ(omp_get_max_active_levels(), levels);
}

// What `body` writes to the file descriptor `fd` (stdout or stderr).
template <class Body>
std::string written_to(int fd, Body body) {
  std::FILE* capture = std::tmpfile();
  if (!capture) return "(no temporary file)";
  std::fflush(nullptr);
  const int saved = dup(fd);
  dup2(fileno(capture), fd);
  body();
  std::fflush(nullptr);
  dup2(saved, fd);
  close(saved);
  std::rewind(capture);
  std::string written;
  for (int c; (c = std::fgetc(capture)) != EOF;) written.push_back(char(c));
  std::fclose(capture);
  return written;
}

// The 3D Laplacian on an m^3 grid.
Eigen::SparseMatrix<double> laplacian_3d(int m) {
  const int n = m * m * m;
  auto id = [m](int i, int j, int k) { return (k * m + j) * m + i; };
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const int a = id(i, j, k);
        t.emplace_back(a, a, 6.0);
        if (i > 0) t.emplace_back(a, id(i - 1, j, k), -1.0), t.emplace_back(id(i - 1, j, k), a, -1.0);
        if (j > 0) t.emplace_back(a, id(i, j - 1, k), -1.0), t.emplace_back(id(i, j - 1, k), a, -1.0);
        if (k > 0) t.emplace_back(a, id(i, j, k - 1), -1.0), t.emplace_back(id(i, j, k - 1), a, -1.0);
      }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// forward_by_start on a reach whose last supernode is a contact face's
// dense trailing block (the top layer of a 3D grid ordered last, 400
// equations), for 600 columns of a few entries each (more than one chunk
// of 256 starting inside that supernode): each column of Y is L^-1 P c of
// its column c of C on the reach's rows, zero above its start, the starts
// ascend; forward() gives the same columns in C's order.
TEST(CholeskyForward, ColumnsSolvedFromTheirFirstRowAreTheFullForwardSolve) {
  const int m = 20;
  const Eigen::SparseMatrix<double> A = laplacian_3d(m);
  std::vector<int> top;
  for (int i = 0; i < m * m; ++i) top.push_back((m - 1) * m * m + i);
  SparseCholesky chol;
  chol.analyze(A, top);
  chol.factorize(A);
  const int cols = 600;
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < cols; ++j)
    for (int e = 0; e < 3; ++e) t.emplace_back(top[(7 * j + 131 * e) % top.size()], j, 1.0 + 0.25 * e + 1e-3 * j);
  Eigen::SparseMatrix<double> C(A.rows(), cols);
  C.setFromTriplets(t.begin(), t.end());
  const SparseCholesky::Reach reach = chol.reach(top);
  const SparseCholesky::ColumnsByStart sorted = chol.forward_by_start(reach, C);
  const Eigen::MatrixXd Y = chol.forward(reach, C);
  ASSERT_EQ(sorted.Y.rows(), Eigen::Index(reach.rows.size()));
  ASSERT_EQ(sorted.Y.cols(), cols);
  EXPECT_TRUE(std::is_sorted(sorted.start.begin(), sorted.start.end()));
  double worst = 0, worst_in_order = 0;
  for (int i = 0; i < cols; ++i) {
    const int j = sorted.order[i];
    const Eigen::VectorXd full = chol.forward_full(Eigen::VectorXd(C.col(j)));
    Eigen::VectorXd expected(reach.rows.size());
    for (std::size_t r = 0; r < reach.rows.size(); ++r) expected[r] = full[reach.rows[r]];
    worst = std::max(worst, (sorted.Y.col(i) - expected).norm() / expected.norm());
    worst_in_order = std::max(worst_in_order, (Y.col(j) - expected).norm() / expected.norm());
    EXPECT_EQ(sorted.Y.col(i).head(sorted.start[i]).norm(), 0.0) << "column " << i;
    EXPECT_NE(sorted.Y(sorted.start[i], i), 0.0) << "column " << i;
  }
  EXPECT_LT(worst, 1e-13);
  EXPECT_LT(worst_in_order, 1e-13);
  // the columns do start inside the trailing supernode, not all at its top
  EXPECT_GT(sorted.start.back() - sorted.start.front(), 200);
}

TEST(CholeskyThreads, IndefiniteMatrixIsAnExceptionAndNothingIsPrinted) {
  bool threw = false;
  const auto factorize_indefinite = [&] {
    try {
      SparseCholesky chol;
      chol.factorize(laplacian(50, -1.0));
    } catch (const std::runtime_error&) {
      threw = true;
    }
  };
  EXPECT_EQ(written_to(fileno(stdout), factorize_indefinite), "");
  EXPECT_TRUE(threw);
  threw = false;
  EXPECT_EQ(written_to(fileno(stderr), factorize_indefinite), "");
  EXPECT_TRUE(threw);
}

TEST(CholeskyPivots, ProductIsTheDeterminantAndANearNullVectorShowsAsOneSmallPivot) {
  // A sum of the logs of n pivots: round-off about n eps.
  constexpr double kLogRoundOff = 1e-12;
  const int n = 200;
  SparseCholesky chol;
  chol.factorize(laplacian(n));
  const Eigen::VectorXd d = chol.pivots();
  ASSERT_EQ(d.size(), n);
  EXPECT_NEAR(d.array().log().sum(), std::log(n + 1.0), kLogRoundOff * n);  // det = n + 1
  EXPECT_LT((2.0 / d.array()).maxCoeff(), 10.0);  // A_ii / pivot_i: nothing nearly singular
  // Shifted to 1e-9 of its smallest eigenvalue above singular: whatever the
  // elimination order, the last pivot of the near-null vector's support
  // keeps about 1e-9 of its stiffness, beyond MAXRATIO's 1e7.
  const int m = 20;
  const double lambda_min = 4 * std::pow(std::sin(std::numbers::pi / (2 * (m + 1))), 2);
  SparseCholesky near;
  near.factorize(laplacian(m, -lambda_min * (1 - 1e-9)));
  EXPECT_GT((2.0 / near.pivots().array()).maxCoeff(), 1e7);
}

}  // namespace
}  // namespace igac
