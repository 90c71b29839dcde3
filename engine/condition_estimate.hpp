// SPDX-License-Identifier: BSD-3-Clause
// The 1-norm condition number kappa_1(A) = ||A||_1 ||A^-1||_1 of a factorised
// matrix, estimated from a few solves with its factor: Hager's method as
// refined by Higham (LAPACK's xLACN2; N. J. Higham, "FORTRAN codes for
// estimating the one-norm of a real or complex matrix", ACM TOMS 14, 1988,
// Algorithm 4.1).  ||A^-1||_1 is the maximum of the convex function
// ||A^-1 x||_1 over the unit 1-norm ball, climbed from x = e/n by at most
// five gradient steps (each one solve with A and one with A^T) plus one
// solve with an alternating-sign vector that catches what the climb misses.
// The estimate is a lower bound, in practice within a factor of 3 of the
// true value (Higham, Accuracy and Stability of Numerical Algorithms,
// sec. 15.3).
//
// Why igac computes it: a backward-stable solve of A x = b gives
// ||dx|| / ||x|| <~ c eps kappa(A) (Higham, ch. 7), so kappa says how many
// digits of the result no machine can promise: a run on another processor,
// BLAS kernel or thread count sums in another order and agrees with this
// one only to that.  summary.json's solver.condition_estimate reports it,
// a near-singular system (a near-mechanism) is warned of, and the tests set
// their tolerances from it (tests/support/solve_tolerance.hpp).
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <functional>

namespace igac {

using VectorSolve = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

// ||A^-1||_1 estimated from x -> A^-1 x and x -> A^-T x (the same function
// for a symmetric A).  0 for n = 0.
double inverse_norm1_estimate(int n, const VectorSolve& solve, const VectorSolve& solve_transpose);

// ||A||_1: the largest column sum of |a_ij|.
double norm1(const Eigen::SparseMatrix<double>& A);
double norm1(const Eigen::MatrixXd& A);

}  // namespace igac
