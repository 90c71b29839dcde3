// SPDX-License-Identifier: BSD-3-Clause
// The PETSc path of a small-deformation run (solvers/petsc_contact), seen
// from solve_model: which elements this process assembles, the load summed
// over the processes, the contact solve in PETSc, and the linear backend of
// the large-deformation Newton driver.  Built also without
// PETSc: then a case that asks for it is a one-line input error.
#pragma once

#include <functional>
#include <memory>

#include "engine/linear_backend.hpp"
#include "model/model.hpp"
#include "model/run_result.hpp"

namespace igac {

bool uses_petsc(const Model& model);
// This process's contiguous block of elements (all of them on one process).
ElementRange process_elements(const Model& model);
// Element loads of every process summed, on every process (no-op on one).
void sum_over_processes(Eigen::VectorXd& f);
// The share of a large-deformation run's elasticity this process evaluates
// (FiniteStrainSetup::share): its block of elements and the sums over
// the processes; empty on one process or without PETSc.
ProcessShare elasticity_share(const Model& model);
// The contact solve in PETSc (op with no rows: the plain linear solve).
// `system.K` is consumed (solve_contact_petsc).  Throws InputError for a bad PETSc option.
ContactSolution solve_with_petsc(const Model& model, LinearSystem& system, const WeightedGapOperator& op,
                                 const RigidModes& modes, const ContactSolverOptions& options,
                                 LinearSolverRecord& record);

// The same with the stiffness whole on every process (the load-curve path
// assembles it once for all steps): K is not consumed.
ContactSolution solve_with_petsc_from_whole(const Model& model, const Eigen::SparseMatrix<double>& K,
                                            const Eigen::VectorXd& f, const WeightedGapOperator& op,
                                            const RigidModes& modes, const ContactSolverOptions& options,
                                            LinearSolverRecord& record);

// The linear backend of a run that asks for PETSc: the large-deformation
// Newton steps (LoadSteppingOptions::linear_backend) and the
// small-deformation friction iterations (SmallStrainFriction) solve whole
// sparse systems with it (solvers/petsc_newton.hpp), every process holding
// the whole matrix and giving PETSc its rows; option errors are InputError
// naming [solver] options.  Null when the case does not ask for PETSc (the
// direct solvers).  Throws InputError when this igac was built without PETSc.
// `after_first_solve` (when given) is called once, after the first solve
// has read the PETSc options: where the console prints its header, so that
// a wrong option stays a one-line input error.
std::unique_ptr<LinearBackend> petsc_linear_backend(const Model& model, std::function<void()> after_first_solve = {});
// What `backend` says of itself, into the run's record (summary.json
// "solver"); the condition estimate where it has one.
void take_report(const LinearBackend& backend, LinearSolverRecord& record);

}  // namespace igac
