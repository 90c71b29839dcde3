// SPDX-License-Identifier: BSD-3-Clause
// The small-deformation contact solve in PETSc, on one or more MPI processes:
// the same primal-dual active set as contact/small_strain_contact (same
// initial set, same rule, same stopping test), but each active-set iteration
// solves the whole saddle-point system in PETSc instead of a dense Schur
// complement read off a CHOLMOD factor:
//
//     [ K + G_A^T W G_A   G_A^T ] [ u ]   [ f - G_A^T W g0_A ]
//     [ G_A               D_I   ] [ l ] = [ -g0_A  (active)  ]
//                                         [  0     (inactive) ]
//
// All m multipliers are unknowns all the time: an inactive one has the row
// D_KK l_K = 0 (D_I diagonal, zero on the active ones) and its G row and
// column are zero, so the matrix keeps one nonzero pattern for the whole
// iteration (a factorisation reuses its symbolic analysis, multigrid its
// setup where the options allow).  The augmentation G_A^T W G_A (W_K =
// E / (h_K^d): the stiffness scale of the face) leaves the solution
// unchanged (G_A u = -g0_A) and makes the displacement block positive
// definite also when the body is held only by contact (Hertz: K alone has
// the free rigid translation in its kernel), which multigrid needs.
//
// Distribution: equations are split in contiguous blocks (PETSc's default
// layout, displacements first, then the multipliers); each process adds the
// stiffness of its own block of elements (MatSetValues, ADD_VALUES, into a
// preallocated MATMPIAIJ) and the contact rows it owns.  The solution is
// gathered to every process, so all of them take the same active-set
// decision and post-process the same result (only the first writes files).
//
// With `spline_multigrid` the assembled matrix is the displacement block
// alone and SplineMultigrid applies the saddle-point operator and its
// block-triangular preconditioner (FGMRES; solvers/petsc_multigrid.hpp).
//
// Options: PETSc's own (`-ksp_type`, `-pc_type`, ...), inserted in the
// options database before the solver reads them.  Default: MUMPS LDL^T on
// the saddle-point matrix (`-ksp_type preonly -pc_type cholesky
// -pc_factor_mat_solver_type mumps`).  With `-pc_type fieldsplit` the two
// fields are named `u` and `lambda` (`-fieldsplit_u_pc_type gamg`) and the
// displacement field carries the rigid-body near null space (from the
// control points) for algebraic multigrid.
#pragma once

#include <stdexcept>
#include <string>

#include "contact/small_strain_contact.hpp"

namespace igac {

// A PETSc option that PETSc refuses (unknown type, bad value) or that no
// PETSc object used (misspelt): a bad input, not a failed solve.
class PetscOptionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// PETSc and MPI, initialised for the lifetime of the object (one per
// program); `options` go to PETSc's options database.  Without a session
// the functions below run as one process.
class PetscSession {
 public:
  explicit PetscSession(const std::string& options);
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;
  static bool active();
  static int rank();
  static int size();
};

// `preconditioner = "algebraic_multigrid"`: FGMRES with a Schur field split
// (full factorisation, the Schur complement approximated by
// B diag(A)^-1 B^T and factorised by MUMPS), one GAMG V-cycle on the
// displacements (with the rigid motions as near null space), as default
// options (the user's override any of them).  A matrix without multipliers
// is all displacements: GAMG on the whole of it.  Call before the solver.
void algebraic_multigrid_defaults();

// This process's contiguous share [begin, end) of n items (elements).
std::pair<int, int> process_share(int n);

struct PetscContactOptions {
  ContactSolverOptions contact;
  double stiffness = 1.0;   // E: the scale of the augmentation W
  int dim = 3;
  // Geometric multigrid from the spline hierarchy (solvers/petsc_multigrid)
  // instead of the options' preconditioner: the prolongations between the
  // nested meshes, finest first (engine/prolongation), whole on every process.
  bool spline_multigrid = false;
  std::vector<Eigen::SparseMatrix<double, Eigen::RowMajor>> prolongations;
};

// K_part and f_part: this process's share (they sum to K and f over the
// processes); K_part is consumed: PETSc works on its own arrays (one
// process, spline multigrid: it ends holding K + G_A^T W G_A) or empties
// it once it holds its copy (taken by reference: Eigen 3.4's SparseMatrix
// has no move constructor, a by-value K was a second copy).  op, modes and
// near_null (n x (3 or 6): rigid motions of the free equations, for
// multigrid) are whole on every process.  Collective.  A Krylov
// solve that does not converge ends the iteration with a failed status;
// throws PetscOptionError for a bad option, std::runtime_error for a PETSc
// failure that is not the solver's (out of memory).
ContactSolution solve_contact_petsc(Eigen::SparseMatrix<double>& K_part, const Eigen::VectorXd& f_part,
                                    const WeightedGapOperator& op, const RigidModes& modes,
                                    const Eigen::MatrixXd& near_null, const PetscContactOptions& options);

}  // namespace igac
