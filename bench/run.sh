#!/usr/bin/env bash
# bench/run.sh [--quick] — benchmarks of igac, written to bench/results/.
#   contact_vs_cholesky.csv: the whole small-deformation contact solve against
#   one sparse Cholesky factorisation of the same matrix (rigid mode pinned),
#   measured in one process, for 2D Hertz from ~34k to ~530k dofs and the
#   default 3D Hertz case (~32k dofs).  --quick stops at ~133k dofs in 2D.  Timings are the best of --repeat runs; the
# machine's other load shows in them, the ratio much less.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
"$here/scripts/bootstrap.sh"
out="$here/bench/results"
mkdir -p "$out"
refines=(2 3 4)
[ "${1:-}" = "--quick" ] && refines=(2 3)
"$here/build/bench/contact_vs_cholesky" "$here/cases/hertz2d.toml" "${refines[@]}" --repeat 2 \
  --csv "$out/contact_vs_cholesky_2d.csv"
"$here/build/bench/contact_vs_cholesky" "$here/cases/hertz3d.toml" 0 --repeat 2 \
  --csv "$out/contact_vs_cholesky_3d.csv"
{ cat "$out/contact_vs_cholesky_2d.csv"; tail -n +2 "$out/contact_vs_cholesky_3d.csv"; } > "$out/contact_vs_cholesky.csv"
rm -f "$out/contact_vs_cholesky_2d.csv" "$out/contact_vs_cholesky_3d.csv"
echo "wrote $out/contact_vs_cholesky.csv"
