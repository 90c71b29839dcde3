#include "engine/cholesky.hpp"

#include <chrono>
#include <stdexcept>

namespace igac {
namespace {
double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

SparseCholesky::SparseCholesky()
    : llt_(std::make_unique<Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>>()) {}

void SparseCholesky::analyze(const Eigen::SparseMatrix<double>& A) {
  const auto t0 = std::chrono::steady_clock::now();
  llt_->analyzePattern(A);
  analyze_s_ = since(t0);
  analyzed_ = true;
}

void SparseCholesky::factorize(const Eigen::SparseMatrix<double>& A) {
  if (!analyzed_) analyze(A);
  const auto t0 = std::chrono::steady_clock::now();
  llt_->factorize(A);
  factorize_s_ = since(t0);
  if (llt_->info() != Eigen::Success)
    throw std::runtime_error(
        "the stiffness matrix is not positive definite: the body can move rigidly "
        "(add Dirichlet conditions or contact) or the data are singular");
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const { return llt_->solve(B); }

}  // namespace igac
