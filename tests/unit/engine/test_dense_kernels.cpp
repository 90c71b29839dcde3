// SPDX-License-Identifier: BSD-3-Clause
// The dense kernels on the system's BLAS and LAPACK (engine/dense_kernels)
// against Eigen's, and the bordered solvers (engine/bordered_spd) against
// a dense LU of the whole bordered system:
//  - gemm (every transpose), gram and the lower-triangular solve on blocks
//    with an outer stride, to round-off; the gram of columns zero above
//    ascending rows;
//  - Lu solves as Eigen's partial-pivoting LU and calls a matrix with a
//    dependent row singular;
//  - BorderedLuSolver with different borders solves the whole system, and
//    with equal borders and a symmetric matrix agrees with
//    BorderedSpdSolver; a border of deficient rank is refused.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "engine/bordered_spd.hpp"
#include "engine/dense_kernels.hpp"

namespace igac {
namespace {

// Round-off of products and solves of these sizes and conditions.
constexpr double kRoundOff = 1e-12;

Eigen::MatrixXd random(int rows, int cols, unsigned seed) {
  std::srand(seed);
  return Eigen::MatrixXd::Random(rows, cols);
}

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).norm() / b.norm(); }

TEST(DenseKernels, GemmEveryTransposeOnStridedBlocks) {
  const Eigen::MatrixXd A = random(40, 30, 1), B = random(30, 40, 2), C0 = random(50, 50, 3);
  for (bool ta : {false, true})
    for (bool tb : {false, true}) {
      const Eigen::MatrixXd a = ta ? Eigen::MatrixXd(A.topRows(30).transpose()) : Eigen::MatrixXd(A.topRows(30));
      const Eigen::MatrixXd b = tb ? Eigen::MatrixXd(B.leftCols(30).transpose()) : Eigen::MatrixXd(B.leftCols(30));
      // op(a) = A.topRows(30) (30 x 30), op(b) = B.leftCols(30) (30 x 30), into a block of C
      Eigen::MatrixXd C = C0;
      dense::gemm(2.0, a, ta, b, tb, 0.5, C.block(5, 7, 30, 30));
      Eigen::MatrixXd expected = C0;
      expected.block(5, 7, 30, 30) = 2.0 * A.topRows(30) * B.leftCols(30) + 0.5 * C0.block(5, 7, 30, 30);
      EXPECT_LT(relative(C, expected), kRoundOff) << "transposes " << ta << tb;
    }
  // a strided block of the operand itself
  Eigen::MatrixXd W(20, 40);
  dense::gemm(1.0, A.bottomRows(20), false, B.leftCols(40), false, 0.0, W);
  EXPECT_LT(relative(W, A.bottomRows(20) * B.leftCols(40)), kRoundOff);
}

TEST(DenseKernels, GramIsYTransposeY) {
  const Eigen::MatrixXd Y = random(200, 60, 4);
  const Eigen::MatrixXd S = dense::gram(Y.middleRows(10, 150));
  EXPECT_LT(relative(S, Y.middleRows(10, 150).transpose() * Y.middleRows(10, 150)), kRoundOff);
  EXPECT_EQ((S - S.transpose()).norm(), 0.0);
}

// Columns zero above ascending starts (the forward solve's on a contact
// face), more than one block of 256 of them: the Gram matrix that skips the
// zeros is Y^T Y.  Starts that do not ascend are refused.
TEST(DenseKernels, GramOfColumnsStartingLowerIsYTransposeY) {
  const int rows = 700, cols = 600;
  Eigen::MatrixXd Y = random(rows, cols, 21);
  std::vector<int> start(cols);
  for (int j = 0; j < cols; ++j) {
    start[j] = j * rows / cols;
    Y.col(j).head(start[j]).setZero();
  }
  const Eigen::MatrixXd S = dense::gram(Y, start);
  EXPECT_LT(relative(S, Y.transpose() * Y), kRoundOff);
  EXPECT_EQ((S - S.transpose()).norm(), 0.0);
  std::swap(start[3], start[400]);
  EXPECT_THROW(dense::gram(Y, start), std::invalid_argument);
}

TEST(DenseKernels, LowerSolveInPlace) {
  Eigen::MatrixXd L = random(60, 30, 5);
  L.topRows(30).diagonal().array() += 30.0;  // well conditioned
  Eigen::MatrixXd X = random(80, 25, 6);
  const Eigen::MatrixXd X0 = X;
  dense::lower_solve_in_place(L.topRows(30), X.middleRows(20, 30));
  const Eigen::MatrixXd Lt = L.topRows(30).triangularView<Eigen::Lower>();
  EXPECT_LT(relative(Lt * X.middleRows(20, 30), X0.middleRows(20, 30)), kRoundOff);
  EXPECT_EQ((X.topRows(20) - X0.topRows(20)).norm(), 0.0);  // rows outside the block untouched
}

TEST(DenseKernels, LuSolvesAndSeesASingularMatrix) {
  const Eigen::MatrixXd A = random(120, 120, 7);
  const Eigen::VectorXd b = random(120, 1, 8);
  dense::Lu lu;
  lu.compute(A);
  ASSERT_FALSE(lu.singular());
  EXPECT_LT(relative(lu.solve(b), A.partialPivLu().solve(b)), 1e-10);
  Eigen::MatrixXd D = A;
  D.row(50) = 0.3 * A.row(3) - 2.0 * A.row(77);  // a dependent row
  lu.compute(D);
  EXPECT_TRUE(lu.singular());
}

// [A -Bc; -Bh^T 0] [x; c] = [r; -q] whole, by Eigen's LU.
void whole_system(const Eigen::MatrixXd& A, const Eigen::MatrixXd& Bc, const Eigen::MatrixXd& Bh,
                  const Eigen::VectorXd& r, const Eigen::VectorXd& q, Eigen::VectorXd& x, Eigen::VectorXd& c) {
  const int n = int(A.rows()), k = int(Bc.cols());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + k, n + k);
  M.topLeftCorner(n, n) = A;
  M.topRightCorner(n, k) = -Bc;
  M.bottomLeftCorner(k, n) = -Bh.transpose();
  Eigen::VectorXd rhs(n + k);
  rhs << r, -q;
  const Eigen::VectorXd sol = M.fullPivLu().solve(rhs);
  x = sol.head(n);
  c = sol.tail(k);
}

TEST(BorderedLuSolver, SolvesTheWholeBorderedSystem) {
  const int n = 90, k = 6;
  Eigen::MatrixXd A = random(n, n, 9);
  A.diagonal().array() += 10.0;
  const Eigen::MatrixXd Bc = random(n, k, 10), Bh = random(n, k, 11);
  const Eigen::VectorXd r = random(n, 1, 12), q = random(k, 1, 13);
  BorderedLuSolver s;
  ASSERT_TRUE(s.compute(A, Bc, Bh));
  Eigen::VectorXd x, c, x_ref, c_ref;
  s.solve(r, q, x, c);
  whole_system(A, Bc, Bh, r, q, x_ref, c_ref);
  EXPECT_LT(relative(x, x_ref), 1e-10);
  EXPECT_LT(relative(c, c_ref), 1e-10);
  EXPECT_LT((Bh.transpose() * x - q).norm(), kRoundOff * q.norm() * Bh.norm());  // the balance to round-off
}

TEST(BorderedLuSolver, EqualBordersOnASymmetricMatrixAgreeWithTheSpdSolver) {
  const int n = 60, k = 3;
  const Eigen::MatrixXd G = random(n, n, 14);
  const Eigen::MatrixXd S = G * G.transpose() + Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd B = random(n, k, 15);
  const Eigen::VectorXd r = random(n, 1, 16), q = random(k, 1, 17);
  BorderedLuSolver lu;
  BorderedSpdSolver spd;
  ASSERT_TRUE(lu.compute(S, B, B));
  ASSERT_TRUE(spd.compute(S, B));
  Eigen::VectorXd x1, c1, x2, c2;
  lu.solve(r, q, x1, c1);
  spd.solve(r, q, x2, c2);
  EXPECT_LT(relative(x1, x2), 1e-10);
  EXPECT_LT(relative(c1, c2), 1e-10);
}

TEST(BorderedLuSolver, RefusesABorderOfDeficientRank) {
  const int n = 40, k = 3;
  Eigen::MatrixXd A = random(n, n, 18);
  A.diagonal().array() += 10.0;
  const Eigen::MatrixXd Bc = random(n, k, 19);
  Eigen::MatrixXd Bh = random(n, k, 20);
  Bh.col(2) = Bh.col(0) - 3.0 * Bh.col(1);  // the multipliers cannot hold one rigid motion
  BorderedLuSolver s;
  EXPECT_FALSE(s.compute(A, Bc, Bh));
  EXPECT_FALSE(s.compute(A, Bh, Bc));
  EXPECT_FALSE(s.compute(A.topLeftCorner(2, 2), Bc.topRows(2), Bc.topRows(2)));  // fewer unknowns than motions
}

}  // namespace
}  // namespace igac
