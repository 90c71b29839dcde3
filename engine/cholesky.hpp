// SPDX-License-Identifier: BSD-3-Clause
// Sparse Cholesky factorisation P A P^T = L L^T of an SPD matrix with CHOLMOD
// (SuiteSparse, supernodal; the dense kernels run on the BLAS that
// libblas.so.3 points to, OpenBLAS when installed).  One object: analyze()
// once per sparsity pattern, factorize() per matrix, then solves.
//
// Equations can be ordered last (constrained AMD, or nested dissection with
// them moved last): they then form the trailing block of the factor.
//
// With any ordering, a right-hand
// side b that is zero outside a few equations gives L^{-1} P b that is zero
// outside the REACH of those equations: their supernodes and all ancestors
// in the supernodal elimination tree (Gilbert & Peierls; Davis, Direct
// Methods for Sparse Linear Systems, ch. 3).  forward() computes Y = L^{-1}
// P C only on such a reach, as dense blocks (per supernode one triangular
// solve and one product for the columns that have started there, a column
// being zero above its first nonzero row); backward() computes
// x = L^{-T} y on a reach from y on the same reach, which is all a caller
// needs for the entries of K^{-1} b at the reach's equations.  The contact
// solvers form G_A K^{-1} G_A^T = Y_A^T Y_A for the active multipliers only;
// with the contact face ordered last, the reach of any face equation is the
// trailing block (a dense triangle of the size of the face).
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
  // An ancestor-closed set of supernodes and their rows (factor positions,
  // ascending; a supernode's columns are consecutive rows).
  struct Reach {
    std::vector<int> supernodes;  // ascending = children before parents
    std::vector<int> rows;
  };
  // The reach of the given (original) equations.
  Reach reach(const std::vector<int>& equations) const;
  // Y = (L^{-1} P C) restricted to reach.rows (rows of Y in that order).
  // Throws std::logic_error when C has a nonzero outside the reach.
  Eigen::MatrixXd forward(const Reach& reach, const Eigen::SparseMatrix<double>& C) const;
  // The same with Y's columns in the order of their first nonzero row:
  // column i is C's column order[i], zero above row start[i] (ascending).
  // Each column is solved from that row down (measured on the contact
  // face's trailing supernode: docs/benchmarks.md, "Friction in 3D"), and
  // dense::gram(Y, start) skips the same zeros.
  struct ColumnsByStart {
    Eigen::MatrixXd Y;
    std::vector<int> order, start;
  };
  ColumnsByStart forward_by_start(const Reach& reach, const Eigen::SparseMatrix<double>& C) const;
  // x = L^{-T} y restricted to reach.rows, from y given on reach.rows.
  Eigen::VectorXd backward(const Reach& reach, const Eigen::VectorXd& y) const;
  // Factor position of an original equation; the number of equations.
  int position(int equation) const;
  int size() const;
  // L^{-1} P b in factor positions (all n), and P^T L^{-T} y back in the
  // original numbering: the two halves of solve().
  Eigen::VectorXd forward_full(const Eigen::VectorXd& b) const;
  Eigen::VectorXd backward_full(const Eigen::VectorXd& y) const;

  // kappa_1 of the last factorised matrix, estimated from about ten solves
  // (engine/condition_estimate.hpp); the factor must exist.
  double condition_estimate() const;
  // After factorize() threw for a matrix not positive definite: the
  // (original) equation whose pivot was not positive, the first in the
  // factor's order; -1 otherwise.
  int indefinite_at() const { return indefinite_at_; }

  // The pivots L_jj^2 of the factor per original equation: what is left of
  // the equation's own stiffness A_ii once every equation before it in the
  // elimination is eliminated.  A_ii / pivot_i large (MSC Nastran's
  // MAXRATIO) says A is nearly singular along a motion that moves that
  // unknown: a near-mechanism.
  Eigen::VectorXd pivots() const;

  bool analyzed() const;
  double analyze_seconds() const { return analyze_s_; }
  double factorize_seconds() const { return factorize_s_; }
  double factor_nonzeros() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double analyze_s_ = 0, factorize_s_ = 0;
  double norm1_ = 0;  // ||A||_1 of the last factorised matrix
  int indefinite_at_ = -1;
};

}  // namespace igac
