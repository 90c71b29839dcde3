#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# scripts/check_doc_commands.sh [--list]
#
# Runs every command that README.md and docs/*.md show in ```sh blocks (also
# indented ones, in a list), as written, and fails when one exits non-zero.
# Each line of such a block is one command; a line whose comment says "not run by the doc check" (the whole
# test suite, benchmarks of minutes) is listed and skipped. The commands run
# in a temporary folder that links the repository's build/, cases/, bench/, examples/,
# scripts/, tests/ and the two top-level scripts, so whatever they write
# (out/, my_part.xml) lands there and is removed at the end. Needs a build
# (./test.sh or ./run.sh makes one). --list prints the commands only.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
list_only=0
[ "${1:-}" = "--list" ] && list_only=1

# The commands, one per line: FILE<TAB>COMMAND.
commands="$(cd "$root" && awk '
  FNR == 1 { block = 0 }
  /^[[:space:]]*```sh[[:space:]]*$/ { block = 1; next }
  /^[[:space:]]*```/ { block = 0; next }
  block && NF && $1 !~ /^#/ { sub(/^[[:space:]]+/, ""); print FILENAME "\t" $0 }
' README.md docs/*.md)"

if [ "$list_only" = 1 ]; then
  printf '%s\n' "$commands"
  exit 0
fi

[ -x "$root/build/igac" ] || { echo "check_doc_commands: no build/igac; run ./test.sh or the build first" >&2; exit 2; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for f in build cases bench scripts tests docs examples run.sh test.sh; do ln -s "$root/$f" "$work/$f"; done

run=0 skipped=0 failed=0
start=$SECONDS
while IFS=$'\t' read -r file cmd; do
  [ -n "$cmd" ] || continue
  if [[ "$cmd" == *"not run by the doc check"* ]]; then
    echo "skip  $file: $cmd"
    skipped=$((skipped + 1))
    continue
  fi
  t0=$SECONDS
  if (cd "$work" && timeout 300 bash -c "$cmd" </dev/null >"$work/.log" 2>&1); then
    echo "ok    $file ($((SECONDS - t0)) s): $cmd"
    run=$((run + 1))
  else
    rc=$?
    echo "FAIL  $file (exit $rc): $cmd"
    sed 's/^/      /' "$work/.log" | tail -20
    failed=$((failed + 1))
  fi
done <<< "$commands"

echo "check_doc_commands: $run ran, $failed failed, $skipped skipped (not run by the doc check), $((SECONDS - start)) s"
[ "$failed" -eq 0 ]
