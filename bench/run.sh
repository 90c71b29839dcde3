#!/usr/bin/env bash
# bench/run.sh [--quick] — benchmarks of igac, written to bench/results/.
#   contact_vs_cholesky.csv: the whole small-deformation contact solve against
#   one sparse Cholesky factorisation of the same matrix (rigid mode pinned),
#   measured in one process, for 2D Hertz from ~34k to ~530k dofs.
# --quick stops at ~133k dofs.  Timings are the best of --repeat runs; the
# machine's other load shows in them, the ratio much less.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
"$here/scripts/bootstrap.sh"
out="$here/bench/results"
mkdir -p "$out"
refines=(2 3 4)
[ "${1:-}" = "--quick" ] && refines=(2 3)
"$here/build/bench/contact_vs_cholesky" "$here/cases/hertz2d.toml" "${refines[@]}" --repeat 3 \
  --csv "$out/contact_vs_cholesky.csv"
echo "wrote $out/contact_vs_cholesky.csv"
