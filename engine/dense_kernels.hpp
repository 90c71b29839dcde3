// SPDX-License-Identifier: BSD-3-Clause
// The large dense kernels of the contact solves on the system's BLAS and
// LAPACK (OpenBLAS in Debian: kernels chosen for the processor at run time,
// threaded), where Eigen's own are compiled for the portable instruction set
// (-march=x86-64-v2) and run on one core: the Gram matrix of the Schur
// complement's columns, the supernodal forward solve on the contact zone and
// the LU of the frictional iteration's dense system (measured:
// docs/benchmarks.md, "Friction in 3D").
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace igac::dense {

using ConstBlock = Eigen::Ref<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
using Block = Eigen::Ref<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;

// C = alpha op(A) op(B) + beta C (op: the transpose where asked).
void gemm(double alpha, const ConstBlock& A, bool transpose_A, const ConstBlock& B, bool transpose_B, double beta,
          Block C);
// Y^T Y, both triangles.
Eigen::MatrixXd gram(const ConstBlock& Y);
// Y^T Y where column j of Y is zero above row start[j] (ascending): the
// products of column blocks skip the rows where one of them is zero.
Eigen::MatrixXd gram(const ConstBlock& Y, const std::vector<int>& start);
// X <- L^-1 X for L lower triangular (its upper part is not read).
void lower_solve_in_place(const ConstBlock& L, Block X);

// A partial-pivoting LU.  singular() when a pivot falls below n eps of the
// largest (the threshold of a full-pivoting LU's rank) or is not finite.
class Lu {
 public:
  void compute(const Eigen::Ref<const Eigen::MatrixXd>& A);  // (a block: no temporary copy)
  bool singular() const { return singular_; }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

 private:
  Eigen::MatrixXd lu_;
  std::vector<int> pivots_;
  bool singular_ = false;
};

}  // namespace igac::dense
