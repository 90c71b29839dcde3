// SPDX-License-Identifier: BSD-3-Clause
// Geometric multigrid from the spline hierarchy for the PETSc solves of
// frictionless contact: the small-deformation active set
// (solvers/petsc_contact) and the Newton steps of large deformation
// (solvers/petsc_newton, which hands it each Newton matrix's displacement
// block and constraint rows); `[solver] preconditioner = "spline_multigrid"`.
//
// The saddle-point system of one active set,
//
//     [ A    G_A^T ] [u]       A = K + G_A^T W G_A  (the displacement block),
//     [ G_A  D_I   ] [l],
//
// is applied as a shell (A, the rows G and the diagonal D; no assembled copy
// of A beside the one multigrid smooths with) and preconditioned by the block
// upper-triangular
//
//     P^-1 r:   z_l = S~^-1 r_l,   z_u = MG(r_u - G_A^T z_l).
//
// S~^-1 is diagonal: on an active multiplier -W_K (the augmented Lagrangian
// argument of Benzi and Olshanskii: with A = K + G^T W G the Schur complement
// is -(M^-1 + W)^-1, M = G K^-1 G^T, so -W approximates its inverse up to the
// factor 1 + M^-1 W^-1, which does not depend on h because W_K = E / h_K^d
// has the scale of K on the face); on an inactive one 1 / D_KK (exact).
//
// MG is one V-cycle of PETSc's PCMG on A over the nested meshes of the case
// (`--refine r`, r - 1, ..., 0): the interpolations are the exact spline
// prolongations (engine/prolongation), the coarse operators Galerkin
// products P^T A P (so the Dirichlet eliminations and the augmentation reach
// every level without a coarse assembly), the smoother Chebyshev on
// ICC(0) per process (block Jacobi on one process, additive Schwarz with
// overlap 2 on several) and the coarsest level a direct solve.  Options
// under the prefix `u_` (`-u_mg_levels_ksp_max_it 3`,
// `-u_mg_levels_pc_type sor`; `-u_pc_mg_levels L` keeps the L finest meshes).
//
// The first guess and the first active set come from the case one
// refinement below (model/solve_small_strain, contact/coarse_start).
#pragma once

#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "solvers/petsc_support.hpp"

namespace igac {

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

class SplineMultigrid {
 public:
  // A: the displacement block (borrowed; the caller keeps its augmentation
  // up to date), G (m x n) and W whole on every process, D_I's values for
  // inactive multipliers, prolongations finest first (P_L: n x n_{L-1}, ...),
  // whole on every process.  Collective.
  SplineMultigrid(Mat A, const RowSparse& G, const Eigen::VectorXd& W, const Eigen::VectorXd& inactive_diagonal,
                  const petsc::SaddleLayout& layout, const std::vector<RowSparse>& prolongations);
  ~SplineMultigrid();
  SplineMultigrid(const SplineMultigrid&) = delete;
  SplineMultigrid& operator=(const SplineMultigrid&) = delete;

  // The contact rows G_A, D_I and S~^-1 of this active set.
  void set_active_set(const std::vector<char>& active);
  // New values of G, W and D_I's (a Newton step's gap derivatives), G of
  // the pattern it was made with; false (nothing changed) if the pattern
  // differs.  Takes effect with the next set_active_set.
  bool set_constraints(const RowSparse& G, const Eigen::VectorXd& W, const Eigen::VectorXd& inactive_diagonal);
  // Gives `ksp` the shell operator and the shell preconditioner (once).
  void attach(KSP ksp);
  // Rebuilds the hierarchy (Galerkin products, smoother estimates, coarse
  // factor) after A changed.
  void setup(bool rebuild = true);
  // PETSc's reason the last setup failed (a singular coarsest level), in
  // words; "" when it did not.
  std::string setup_failure() const;
  int levels() const { return int(P_.size()) + 1; }
  Mat shell() const;  // the saddle-point operator (after attach)

 private:
  static PetscErrorCode mult(Mat S, Vec x, Vec y);
  static PetscErrorCode apply(PC pc, Vec r, Vec z);
  PetscErrorCode on_parts(Vec x, Vec y, PetscErrorCode (SplineMultigrid::*part)());
  PetscErrorCode operator_parts();
  PetscErrorCode preconditioner_parts();

  Mat A_;
  petsc::SaddleLayout layout_;
  RowSparse G_;
  Eigen::VectorXd W_, inactive_;
  petsc::OwnedMat B_, S_;              // G_A (m x n, rows [l0, l1)), the shell
  std::vector<petsc::OwnedMat> P_;     // coarse to fine, P_[0] into level 1
  petsc::OwnedVec d_, sinv_, xu_, xl_, yu_, yl_, tu_, tl_;
  petsc::OwnedKSP mg_;
};

}  // namespace igac
