#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# scripts/mpirun.sh N ARGS...   — runs `build/igac ARGS` on N MPI processes.
#   scripts/mpirun.sh 2 run cases/hertz3d.toml --solver petsc
# Open MPI refuses to start as root without --allow-run-as-root and more
# processes than cores without --oversubscribe; both are set here (through
# its environment, so a plain `mpirun` in the same shell works too), with one
# thread per process for OpenMP and OpenBLAS unless the caller chose.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[ $# -ge 2 ] || { echo "usage: scripts/mpirun.sh N run CASE.toml --solver petsc [options]" >&2; exit 2; }
n="$1"; shift
[[ "$n" =~ ^[1-9][0-9]*$ ]] || { echo "scripts/mpirun.sh: the process count must be a whole number >= 1 (got '$n')" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}" OPENBLAS_NUM_THREADS="${OPENBLAS_NUM_THREADS:-1}"
# Each run its own session directory: two mpiruns starting at once race to
# create the shared /tmp/ompi.HOST.UID and one fails with "File exists"
# (seen under ctest -j2).  Removed when the run ends.
if [ -z "${OMPI_MCA_orte_tmpdir_base:-}" ]; then
  session="$(mktemp -d "${TMPDIR:-/tmp}/igac-mpi.XXXXXX")"
  trap 'rm -rf "$session"' EXIT
  export OMPI_MCA_orte_tmpdir_base="$session"
fi
mpirun -n "$n" "${IGAC_BINARY:-$here/build/igac}" "$@"
