#!/usr/bin/env bash
# CI stage: valgrind memcheck on the sfit CLI of the normal build (BUILD_DIR, default build)
# on two data sets (open rows; closed ragged rows), plus one error path. Any memcheck error
# or definite leak fails the stage (--error-exitcode).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
cli="${BUILD_DIR:-build}/apps/sfit/sfit"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
vg=(valgrind --tool=memcheck --error-exitcode=99 --leak-check=full
    --errors-for-leak-kinds=definite,indirect --show-leak-kinds=definite,indirect
    --track-origins=yes -q)
start=$(date +%s)
check() {
  local expected=$1
  shift
  local rc=0
  "${vg[@]}" "$cli" "$@" 2>"$out/log" || rc=$?
  if [ "$rc" -ne "$expected" ]; then
    cat "$out/log"
    echo "valgrind: FAILED (exit $rc, expected $expected): sfit $*"
    exit 1
  fi
  echo "valgrind: clean (exit $rc): sfit $*"
}
check 0 fit examples/ship_px121_stations.rows -q -o "$out/hull.json" --report "$out/report.json"
check 0 fit examples/iea3p4mw_blade_ragged9.rows --closed u --tol 0.001 -q -o "$out/blade.json"
check 0 convert "$out/hull.json" -q -o "$out/hull-copy.json"
check 4 fit tests/bad_input/truncated_last_line.rows -q -o "$out/bad.json"
# The optional writers, where this build has them: STEP (OpenCASCADE), STL, PNG (libpng).
extra=()
"$cli" convert "$out/hull.json" -q -o "$out/probe.step" 2>/dev/null && extra+=(-o "$out/hull.step" -o "$out/hull.stl")
"$cli" fit --help 2>/dev/null | grep -q -- '--png' && extra+=(--png "$out/hull.png")
if [ ${#extra[@]} -gt 0 ]; then
  check 0 fit examples/ship_px121_stations.rows -q "${extra[@]}"
fi
echo "valgrind: $(($(date +%s) - start)) s"
