#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs the Debian 12 packages igac builds against (when they are missing
# and we are root), then configures and builds Release into build/ when the
# sources are newer than the binary. Shared by run.sh and test.sh.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

packages=(cmake g++ make pkg-config
          libeigen3-dev libsundials-dev libsuitesparse-dev libvtk9-dev
          libfmt-dev libtomlplusplus-dev libcli11-dev libgtest-dev
          nlohmann-json3-dev libpugixml-dev libopenblas0-pthread libopenblas-dev
          python3 python3-matplotlib     # the plots of bench/*.py (igac writes its own as SVG)
          python3-dev pybind11-dev python3-numpy  # the Python module (python/, docs/python.md)
          libpetsc-real-dev openmpi-bin)   # the PETSc (MPI) solver path: --solver petsc, scripts/mpirun.sh

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

build="$here/build"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release >&2
fi
cmake --build "$build" -j "$(nproc)" >&2
