// SPDX-License-Identifier: BSD-3-Clause
// The PETSc path of a small-deformation run (solvers/petsc_contact), seen
// from solve_model: which elements this process assembles, the load summed
// over the processes, the contact solve in PETSc, and the linear backend of
// the large-deformation Newton driver.  Built also without
// PETSc: then a case that asks for it is a one-line input error.
#pragma once

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
// The contact solve in PETSc (op with no rows: the plain linear solve).
// `system.K` is consumed (solve_contact_petsc).  Throws InputError for a bad PETSc option.
ContactSolution solve_with_petsc(const Model& model, LinearSystem& system, const WeightedGapOperator& op,
                                 const RigidModes& modes, const ContactSolverOptions& options,
                                 LinearSolverRecord& record);

// The linear solver of a large-deformation run's Newton steps
// (LoadSteppingOptions::linear_backend): PETSc's (solvers/petsc_newton.hpp)
// when the case asks for PETSc, whose option errors it reports as
// InputError naming [solver] options; null otherwise (the driver's direct
// one).  Throws InputError when this igac was built without PETSc.
std::unique_ptr<LinearBackend> newton_linear_solver(const Model& model);

}  // namespace igac
