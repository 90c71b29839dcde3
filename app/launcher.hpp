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

#include <string>

namespace igac {

// 0 and 1 without a launcher.
int launcher_rank();
int launcher_size();

// SIGTERM, SIGINT and SIGHUP end the program, whatever library runs when
// they come (those not set to be ignored by the parent, as nohup does with
// SIGHUP): they are blocked in every thread and one thread of their own
// waits for them, prints "igac: stopped by SIGTERM" and ends the process
// with status 128 + signal (143 for SIGTERM), as a shell reports it.
// (METIS, inside CHOLMOD's ordering, installs a SIGTERM handler of its own
// for its error returns: a SIGTERM that came then was swallowed, and the
// run went on.)  Threads inherit the blocked mask from the thread that
// starts them.
void end_on_termination_signals();
// A folder that thread removes before it ends the process (the staging
// folder of app/output_folder.hpp, so that a run stopped by SIGTERM leaves
// nothing behind); "" removes nothing.
void remove_on_termination(const std::string& folder);
// Libraries start threads before main (OpenBLAS's pool, in its loader
// constructor), with the signals unblocked: such a thread would take a
// SIGTERM and run the library handler of the moment there (METIS's longjmp
// into another thread: a crash).  So the program re-executes itself once
// with the signals blocked (a blocked mask survives exec, and every thread
// of the new image inherits it); returns when they already were blocked or
// exec failed.  The first call of main.
void block_termination_signals_in_every_thread(char** argv);

// Replaces this process by igac-petsc (next to this executable) with the
// same arguments; returns only when there is no igac-petsc (built without
// PETSc).  Throws std::runtime_error when exec fails.
void hand_over_to_petsc_build(char** argv);

}  // namespace igac
