#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# scripts/bootstrap.sh [run | petsc | all]   (default: all)
# Installs the Debian 12 packages igac needs for what is asked (when they are
# missing and we are root), configures a Release build in build/ and builds
# what is asked when it is out of date:
#   run    what a direct run needs; the igac program only (./run.sh)
#   petsc  that and PETSc with Open MPI; igac-petsc too (--solver petsc, scripts/mpirun.sh)
#   all    everything: PETSc, the test suite (GoogleTest), the Python module,
#          the benchmarks' plots; every target (./test.sh, bench/run.sh, CI)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode="${1:-all}"

run_packages=(cmake g++ make pkg-config
              libeigen3-dev libsundials-dev libsuitesparse-dev libvtk9-dev
              libfmt-dev libtomlplusplus-dev libcli11-dev
              nlohmann-json3-dev libpugixml-dev libopenblas0-pthread libopenblas-dev)
petsc_packages=(libpetsc-real-dev openmpi-bin)   # the PETSc (MPI) solver path
more_packages=(libgtest-dev                        # the test suite
               python3 python3-matplotlib          # the plots of bench/*.py (igac writes its own as SVG)
               python3-dev pybind11-dev python3-numpy)  # the Python module (python/, docs/python.md)

case "$mode" in
  run)   packages=("${run_packages[@]}"); targets=(--target igac)
         options=() ;;
  petsc) packages=("${run_packages[@]}" "${petsc_packages[@]}"); targets=(--target igac igac-petsc)
         options=(-DIGAC_WITH_PETSC=ON) ;;
  all)   packages=("${run_packages[@]}" "${petsc_packages[@]}" "${more_packages[@]}"); targets=()
         options=(-DIGAC_WITH_PETSC=ON -DIGAC_BUILD_TESTS=ON) ;;
  *)     echo "usage: scripts/bootstrap.sh [run | petsc | all]" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "igac: missing Debian packages: ${missing[*]} (run as root, or: sudo apt-get install ${missing[*]})" >&2
    exit 1
  fi
  echo "igac: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq >&2
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

# A first configuration for a run leaves the tests out (GoogleTest is not
# installed for it); petsc and all configure again with what they add, so a
# build/ that ./run.sh started serves ./test.sh (PETSc found once installed).
build="$here/build"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release \
        "-DIGAC_BUILD_TESTS=$([ "$mode" = all ] && echo ON || echo OFF)" "${options[@]}" >&2
elif [ ${#options[@]} -gt 0 ]; then
  cmake -S "$here" -B "$build" "${options[@]}" >&2
fi
cmake --build "$build" -j "$(nproc)" "${targets[@]}" >&2
