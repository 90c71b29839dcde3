// SPDX-License-Identifier: BSD-3-Clause
// How many threads one of igac's parallel regions (assembly, stress
// recovery, error norms, the sparsity pattern) takes: the threads OpenMP
// may use (OMP_NUM_THREADS, else the processors) less the threads of other
// processes that are runnable right now, at least one: /proc/stat's
// procs_running less this process's own runnable threads (the caller, and
// an OpenMP or OpenBLAS worker still spinning after its last region, which
// waits for this one: counted as busy, every region after another ran on
// one thread).  Read at the start
// of each region: under `ctest -j2` or beside another job a region does
// not oversubscribe the cores (busy-waiting teams larger than the idle
// cores cost several times the work: measured 3x on 2 shared cores), and
// on an idle machine it takes them all.  Not libgomp's dynamic mode: that
// one reads the 15-minute load average, so for a quarter of an hour after
// any busy spell (igac's own run included) every region ran on one thread
// (docs/design.md, "Threads and memory").
#pragma once

namespace igac {

int free_cores();

}  // namespace igac
