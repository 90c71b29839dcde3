#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# bench/run.sh [--quick] — benchmarks of igac, written to bench/results/.
#   contact_vs_cholesky.csv: the whole small-deformation contact solve against
#   one sparse Cholesky factorisation of the same matrix (rigid mode pinned),
#   measured in one process, for 2D Hertz from ~34k to ~530k dofs and the
#   default 3D Hertz case (~32k dofs).  --quick stops at ~133k dofs in 2D.  Timings are the best of --repeat runs; the
# machine's other load shows in them, the ratio much less.
#   newton_vs_linear.csv: one large-deformation Newton iteration against one
#   small-deformation solve of the same mesh (2D pressure and displacement
#   cases, refine 0-1, --quick refine 0; 3D Neo-Hookean octant).
#   master_search.csv: the closest-point search of two-body contact on 1k-16k
#   master elements, the tree against trying every element.
#   stress_tests.csv / .md: bench/stress_test.py, numerical stability under
#   stress (loads, degrees, grading, nu, load steps, initial gaps).
#   work_precision.csv / *.png: bench/work_precision.py, error against time
#   and time against dofs for 2D and 3D Hertz.
# --quick is passed to all three; it finishes within 10 minutes on 2 cores.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
"$here/scripts/bootstrap.sh"
out="$here/bench/results"
mkdir -p "$out"
refines=(2 3 4)
quick=()
[ "${1:-}" = "--quick" ] && refines=(2 3) && quick=(--quick)
SECONDS=0
"$here/build/bench/contact_vs_cholesky" "$here/cases/hertz2d.toml" "${refines[@]}" --repeat 2 \
  --csv "$out/contact_vs_cholesky_2d.csv"
"$here/build/bench/contact_vs_cholesky" "$here/cases/hertz3d.toml" 0 --repeat 2 \
  --csv "$out/contact_vs_cholesky_3d.csv"
{ cat "$out/contact_vs_cholesky_2d.csv"; tail -n +2 "$out/contact_vs_cholesky_3d.csv"; } > "$out/contact_vs_cholesky.csv"
rm -f "$out/contact_vs_cholesky_2d.csv" "$out/contact_vs_cholesky_3d.csv"
echo "wrote $out/contact_vs_cholesky.csv"
echo "contact_vs_cholesky: ${SECONDS} s"

t0=$SECONDS
nrefines=(0 1)
[ "${1:-}" = "--quick" ] && nrefines=(0)
: > "$out/newton_vs_linear.csv"
for c in hertz2d_neohookean_pressure hertz2d_neohookean_displacement hertz3d_neohookean; do
  r=("${nrefines[@]}")
  [ "$c" = hertz3d_neohookean ] && r=(0)
  "$here/build/bench/newton_vs_linear" "$here/cases/$c.toml" "${r[@]}" --repeat 2 --csv "$out/nvl_$c.csv"
  if [ -s "$out/newton_vs_linear.csv" ]; then tail -n +2 "$out/nvl_$c.csv"; else cat "$out/nvl_$c.csv"; fi >> "$out/newton_vs_linear.csv"
  rm -f "$out/nvl_$c.csv"
done
echo "wrote $out/newton_vs_linear.csv"
echo "newton_vs_linear: $((SECONDS - t0)) s"
"$here/build/bench/master_search" 32 64 128 --queries 400 --csv "$out/master_search.csv"

# Python benchmarks: Debian's interpreter has matplotlib.
rc=0
t0=$SECONDS
/usr/bin/python3 "$here/bench/stress_test.py" "${quick[@]}" --igac "$here/build/igac" || rc=1
echo "stress_test: $((SECONDS - t0)) s"
t0=$SECONDS
/usr/bin/python3 "$here/bench/work_precision.py" "${quick[@]}" --igac "$here/build/igac" || rc=1
echo "work_precision: $((SECONDS - t0)) s"
echo "bench/run.sh ${quick[*]}: ${SECONDS} s in all"
exit $rc
