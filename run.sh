#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# ./run.sh CASE [options]   — set up (the packages a run needs, the igac
# program) when needed, run one case.  Options are those of `build/igac run`
# (--out DIR, --refine N, --degree P, --quiet, --no-output, --solver ...);
# --solver petsc needs `scripts/bootstrap.sh petsc` once.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
"$here/scripts/bootstrap.sh" run
[ $# -ge 1 ] || { echo "usage: ./run.sh CASE.toml [--out DIR] [--refine N] [--degree P] [--quiet]" >&2; exit 2; }
exec "$here/build/igac" run "$@"
