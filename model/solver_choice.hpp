// SPDX-License-Identifier: BSD-3-Clause
// Which linear solver runs a case: the rules that refuse a combination
// (one line each), and the choice `preconditioner = "auto"` makes.
#pragma once

#include <string>
#include <string_view>

#include "model/case_spec.hpp"
#include "model/memory_estimate.hpp"

namespace igac {

// Why a [solver] preconditioner cannot be used ("" when it can), and the
// message for a name that is none.
std::string check_preconditioner(const SolverSpec& solver);
std::string unknown_preconditioner(const std::string& name);
// Sets `solver`'s preconditioner from its name ("auto" included); false for
// a name that is none.
bool set_preconditioner(SolverSpec& solver, std::string_view name);
// Why the PETSc solver cannot run this case ("" when it can): it runs every
// large-deformation case (each Newton step's linear solve in PETSc) and the
// small-deformation solve of solve_model frictionless, without load curves
// (two bodies, several contacts, the mixed formulation and moving obstacles
// included).  The one rule of [solver] type = "petsc" and of --solver petsc.
std::string check_petsc_case(const CaseSpec& c);

// The case at its final mesh (--refine applied): `auto` becomes the spline
// multigrid where it is the faster of the two on the measurements of
// docs/petsc.md ("Choosing the preconditioner"): a 3D mesh of at least
// kMultigridUnknowns unknowns refined at least once (the hierarchy), or
// one whose factorisation would not fit in `memory_bytes` (the machine's by
// default) where the multigrid's would, and a case the
// multigrid runs (frictionless, no ties, no load curves in small
// deformation, no -pc_type or -ksp_type in the options); a factorisation
// (MUMPS) otherwise.  c.solver.choice says which and why.  Without auto,
// nothing changes.  Then, for the spline multigrid, a -u_pc_mg_levels in
// the options asks for at most the case's meshes (InputError otherwise).
inline constexpr double kMultigridUnknowns = 100000;
void settle_preconditioner(CaseSpec& c, double memory_bytes = physical_memory_bytes());

}  // namespace igac
