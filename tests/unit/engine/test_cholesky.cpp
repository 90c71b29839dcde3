// SPDX-License-Identifier: BSD-3-Clause
// engine/cholesky around its CHOLMOD calls: during a call OpenMP regions are
// serialised and OpenBLAS gets as many threads as the work pays for; after
// it both are as they were (the assembly's threads must not stay off), and
// CHOLMOD never prints (its warnings go to stdout, where a run's summary is
// read by people and scripts; an indefinite matrix is an exception the
// caller handles, e.g. the Newton path's fallback, not a warning line).
#include <gtest/gtest.h>

#include <cstdio>
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

}  // namespace
}  // namespace igac
