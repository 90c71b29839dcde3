// SPDX-License-Identifier: BSD-3-Clause
// How many threads one of igac's parallel regions (assembly, stress
// recovery, error norms, the sparsity pattern) takes: the threads OpenMP
// may use (OMP_NUM_THREADS, else the processors) less the threads of other
// processes that are runnable right now, at least one.  Those are
// /proc/stat's procs_running less this process's own runnable threads: the
// caller, and OpenMP workers that still spin after the last region and
// will run this one (counted as other work, they put every region after
// another on one thread).  An OpenBLAS worker spinning after a BLAS call is
// counted as this process's too, though it does hold a core until it
// sleeps.  Read at the start of each threaded region (a few tens of
// microseconds): under `ctest -j2` or beside another job a region does not
// oversubscribe the cores, and on an idle machine it takes them all.  Not
// libgomp's dynamic mode, which reads the 15-minute load average (docs/design.md,
// "Threads and memory").
#pragma once

namespace igac {

int free_cores();

}  // namespace igac
