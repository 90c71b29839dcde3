// SPDX-License-Identifier: BSD-3-Clause
// How this process was started: its rank among the processes of mpirun
// (read from the launcher's environment, before or without MPI), and the
// hand-over from the plain igac program to igac-petsc.
//
// igac is built twice from the same sources: `igac`, without PETSc and MPI,
// which starts in a few milliseconds (PETSc brings about 100 shared
// libraries, and loading them costs a sizeable share of a small 2D run;
// measured: docs/petsc.md, "The PETSc path"), and
// `igac-petsc`, the same program with the PETSc solver path.  A run that
// asks for PETSc (--solver petsc, or [solver] type = "petsc") is handed
// from the first to the second with the same arguments, in the same process
// (exec), so mpirun and the user see one program.
#pragma once

namespace igac {

// 0 and 1 without a launcher.
int launcher_rank();
int launcher_size();

// Replaces this process by igac-petsc (next to this executable) with the
// same arguments; returns only when there is no igac-petsc (built without
// PETSc).  Throws std::runtime_error when exec fails.
void hand_over_to_petsc_build(char** argv);

}  // namespace igac
