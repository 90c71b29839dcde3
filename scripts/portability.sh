#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# scripts/portability.sh [BUILD] [-- CTEST ARGS]
#
# Runs the whole test suite once per OpenBLAS kernel (OPENBLAS_CORETYPE =
# Haswell, SkylakeX, Sandybridge, Zen) and thread count (OMP_NUM_THREADS = 1,
# 2): no test may depend on the processor, the BLAS kernel or the thread
# count (tests/support/solve_tolerance.hpp says how tolerances follow from
# the solve instead).  The golden tests print how much of their tolerance
# each run used; the largest per configuration is collected at the end.
# Writes BUILD/portability/<kernel>_<threads>.log and a table
# BUILD/portability/summary.csv; exits non-zero if any configuration fails.
# A kernel the processor cannot run (SkylakeX needs AVX-512) is skipped and
# said so.  Takes 8 suite runs: about 40 minutes on two cores.
set -uo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
[ $# -gt 0 ] && shift
[ "${1:-}" = "--" ] && shift
[ -x "$build/tests/igac_tests" ] || { echo "portability: no $build/tests/igac_tests (build first: ./test.sh or cmake --build)" >&2; exit 2; }
out="$build/portability"
mkdir -p "$out"
echo "kernel,openblas_took,threads,result,tests_failed,largest_golden_diff_over_tolerance,at" > "$out/summary.csv"

status=0
for kernel in Haswell SkylakeX Sandybridge Zen; do
  # OpenBLAS falls back to another kernel (or dies) when the CPU lacks the
  # kernel's instructions: ask it which core it took.
  took=$(OPENBLAS_CORETYPE=$kernel OPENBLAS_VERBOSE=2 "$build/igac" --version 2>&1 | sed -n 's/^Core: //p' | head -n 1)
  if [ "$kernel" = SkylakeX ] && ! grep -q avx512f /proc/cpuinfo; then
    echo "portability: $kernel skipped: this processor has no AVX-512" >&2
    echo "$kernel,-,-,skipped (no AVX-512),,," >> "$out/summary.csv"
    continue
  fi
  for threads in 1 2; do
    log="$out/${kernel}_${threads}.log"
    echo "portability: OPENBLAS_CORETYPE=$kernel (OpenBLAS took: ${took:-unknown}), OMP_NUM_THREADS=$threads" >&2
    (cd "$build" && OPENBLAS_CORETYPE=$kernel OMP_NUM_THREADS=$threads ctest -j 2 --output-on-failure -V "$@") > "$log" 2>&1
    rc=$?
    failed=$(sed -n 's/.*tests passed, \([0-9]*\) tests failed out of.*/\1/p' "$log" | tail -n 1)
    # "...largest |diff| / tolerance: results R (WHERE), CSV files C (..)": the largest R or C
    worst=$(grep -o 'largest |diff| / tolerance: results [^ ]* ([^)]*), CSV files [^ ]* ([^)]*)' "$log" |
            awk '{ for (i = 1; i <= NF; ++i) if ($i == "results" || $i == "files") { v = $(i + 1); w = $(i + 2); j = i + 2;
                     while (w !~ /\)/ && j < NF) { j++; w = w " " $j }; sub(/[,;]$/, "", w);
                     if (v + 0 > best) { best = v + 0; at = w } } }
                 END { printf "%g,%s", best, at }')
    result=passed; [ $rc -ne 0 ] && { result=FAILED; status=1; }
    echo "$kernel,${took:-unknown},$threads,$result,${failed:-?},$worst" >> "$out/summary.csv"
    echo "portability:   $result (${failed:-?} failed); largest golden |diff| / tolerance ${worst%%,*}" >&2
  done
done
column -s, -t < "$out/summary.csv"
exit $status
