#!/usr/bin/env bash
# CI stage: scripts/deps/build.txt (all that scripts/build-and-run.sh installs on a bare
# Debian 12 machine) suffices to build the CLI. scripts/check_build_deps.py maps every header,
# library and tool the CLI's build used (ninja's dependency records, the link, ldd,
# CMakeCache.txt) to its Debian package and requires each to be in build.txt or a dependency
# of it; its header says why this and not a debootstrap clean root (minutes and the network
# per run). Then the check shows it can fail: with coinor-libclp-dev taken out of the list it
# must name that package. A few seconds on top of the main build (folder build/).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
fail() { echo "build-deps: FAILED: $*" >&2; exit 1; }
cmake --build build --target sfit_cli >/dev/null
/usr/bin/python3 scripts/check_build_deps.py --build build --list scripts/deps/build.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
grep -v '^coinor-libclp-dev' scripts/deps/build.txt >"$tmp/build.txt"
if /usr/bin/python3 scripts/check_build_deps.py --build build --list "$tmp/build.txt" >"$tmp/out"; then
  fail "the check passed without coinor-libclp-dev in the list"
fi
grep -q '^  coinor-libclp-dev: not in' "$tmp/out" || fail "the check did not name coinor-libclp-dev: $(cat "$tmp/out")"
echo "build-deps: a list without coinor-libclp-dev fails, naming it"
