// Sparse Cholesky factorisation P A P^T = L L^T of an SPD matrix with CHOLMOD
// (SuiteSparse, supernodal; the dense kernels run on the BLAS that
// libblas.so.3 points to, OpenBLAS when installed).  One object: analyze()
// once per sparsity pattern, factorize() per matrix, then solves.
//
// Equations can be ordered last (CAMD constrained ordering).  Then for any
// C whose rows are zero outside those equations,
//     C^T A^{-1} C = Y^T Y,   Y = L_TT^{-1} (P C)_T,
// where T is the trailing block of the factor: the contact solver gets the
// Schur complement G K^{-1} G^T of all multipliers from a dense triangular
// solve of the size of the contact face, instead of one sparse solve per
// multiplier.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <memory>
#include <vector>

namespace igac {

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // Symbolic analysis (fill-reducing ordering, supernodes): CHOLMOD's choice
  // of ordering, or, when `last` is not empty, AMD constrained to put those
  // equations after all others.  Valid for every matrix of the same pattern.
  void analyze(const Eigen::SparseMatrix<double>& A, const std::vector<int>& last = {});
  // Numeric factorisation (analyses first if needed).  Throws
  // std::runtime_error when A is not positive definite.
  void factorize(const Eigen::SparseMatrix<double>& A);
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  // Y = L_TT^{-1} (P C)_T (see above).  Throws std::logic_error when C has a
  // nonzero outside the trailing block.
  Eigen::MatrixXd half_solve_trailing(const Eigen::SparseMatrix<double>& C) const;
  // Size of the trailing block that holds the equations ordered last.
  int trailing_size() const { return trailing_size_; }

  bool analyzed() const;
  double analyze_seconds() const { return analyze_s_; }
  double factorize_seconds() const { return factorize_s_; }
  double factor_nonzeros() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int trailing_size_ = 0;
  double analyze_s_ = 0, factorize_s_ = 0;
};

}  // namespace igac
