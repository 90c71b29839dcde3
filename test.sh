#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# ./test.sh   — set up (every package the suite needs, PETSc included, and
# every target) when needed, then run the whole suite through CTest.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
"$here/scripts/bootstrap.sh" all
cd "$here/build"
ctest --output-on-failure -j "$(nproc)" "$@"
