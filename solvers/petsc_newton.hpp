// SPDX-License-Identifier: BSD-3-Clause
// The PETSc linear backend of the load-stepping Newton driver
// (engine/linear_backend.hpp): each Newton matrix, in blocks
// (engine/block_jacobian.hpp), is condensed (the element-local unknowns of
// the mixed formulation eliminated, as the direct backend does) and handed
// to PETSc as one sparse matrix of n + m rows (displacements, then every
// multiplier: an inactive one has its row d_k dl_k, an active one s_k B_k du),
// split in contiguous blocks of rows over the MPI processes.
//
// Where K is symmetric (no follower load, no slip rows, no coupling outside
// K) the matrix is put in a symmetric form (active rows divided by their
// scale, inactive multipliers' columns moved to the right-hand side: the
// same solution) and factorised by MUMPS as L D L^T; otherwise (a follower
// load, friction, two bodies' curvature coupling) by MUMPS LU.  Any KSP
// and PC the PETSc options name replace these (`-ksp_type gmres -pc_type
// ilu` ...), and an iterative one is asked for the driver's inexact-Newton
// tolerance.  With an iterative PC (any but lu and cholesky) the active
// rows are also added to the displacement block as an augmented Lagrangian,
// B_A^T W (B_A du - c_A) = 0, the same solution with a definite block where
// only contact holds a body (algebraic multigrid needs it); a field split
// (`-pc_type fieldsplit`, or `preconditioner = "algebraic_multigrid"`) gets
// the fields `u` and `lambda` and the rigid motions of each body as u's
// near null space, and a matrix without multipliers is all field u.
// Friction's and ties' matrices (BlockJacobian::general) have no fields
// apart: a field split is refused there.  Given a spline hierarchy, the
// displacement block K + B_A^T W B_A alone is assembled and FGMRES runs
// with SplineMultigrid (solvers/petsc_multigrid.hpp) on the constraint form.
// Any Krylov solve stops on the residual of J itself, not of the modified
// matrix PETSc iterates on.  While the pattern of the
// matrix stays (it does unless the active set changes which rows a curved
// master couples), the matrix is refilled in place and the factorisation
// keeps its symbolic analysis; a new pattern builds a new matrix.
//
// Every process evaluates the whole problem (the residual and the blocks
// are the same bits on all of them) and gives PETSc the rows it owns; the
// solution is gathered to every process, so all of them take the same
// Newton and active-set decisions.  Needs a PetscSession
// (solvers/petsc_contact.hpp).
#pragma once

#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/linear_backend.hpp"

namespace igac {

class PetscNewtonSolver final : public LinearBackend {
 public:
  // near_null: the displacements' rigid motions (n x 3 or 6 per body),
  // for algebraic multigrid in a field split (-fieldsplit_u_pc_type gamg);
  // may be empty.  spline_hierarchy: the prolongations of the spline
  // multigrid (solvers/petsc_multigrid.hpp), finest first; given, every
  // Newton matrix is solved by FGMRES with it (frictionless only).
  explicit PetscNewtonSolver(Eigen::MatrixXd near_null = {},
                             std::optional<std::vector<Eigen::SparseMatrix<double, Eigen::RowMajor>>>
                                 spline_hierarchy = std::nullopt);
  ~PetscNewtonSolver() override;
  PetscNewtonSolver(const PetscNewtonSolver&) = delete;
  PetscNewtonSolver& operator=(const PetscNewtonSolver&) = delete;

  // Collective.  Throws PetscOptionError (solvers/petsc_contact.hpp) for an
  // option PETSc refuses or that nothing used (after the first solve).
  bool setup(const BlockJacobian& J) override;
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance) override;
  const std::string& why() const override { return why_; }
  const LinearSolveStats& stats() const override { return stats_; }
  double condition_estimate() const override { return 0; }  // not estimated
  LinearBackendReport report() const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string why_;
  LinearSolveStats stats_;
};

}  // namespace igac
