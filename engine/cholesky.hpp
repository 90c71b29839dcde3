// Sparse Cholesky factorisation of an SPD matrix with CHOLMOD (SuiteSparse),
// through Eigen's CholmodSupport: symbolic analysis (fill-reducing ordering,
// supernodes) once per sparsity pattern, numeric factorisation per matrix,
// then any number of solves with one or many right-hand sides (the dense
// kernels run on the BLAS that libblas.so.3 points to; OpenBLAS here).
#pragma once

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <memory>

namespace igac {

class SparseCholesky {
 public:
  SparseCholesky();
  // Symbolic analysis; valid for every matrix of the same pattern.
  void analyze(const Eigen::SparseMatrix<double>& A);
  // Numeric factorisation (analyses first if needed).  Throws
  // std::runtime_error when A is not positive definite (e.g. a body whose
  // rigid motions are not held).
  void factorize(const Eigen::SparseMatrix<double>& A);
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  bool analyzed() const { return analyzed_; }
  double analyze_seconds() const { return analyze_s_; }
  double factorize_seconds() const { return factorize_s_; }

 private:
  std::unique_ptr<Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>> llt_;
  bool analyzed_ = false;
  double analyze_s_ = 0, factorize_s_ = 0;
};

}  // namespace igac
