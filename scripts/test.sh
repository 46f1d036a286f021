#!/usr/bin/env bash
# Installs the dependencies, builds sfit with its tests, and runs the whole test suite.
# Each stage in scripts/test.d/ (run in name order) adds a further check: sanitizers, fuzzing.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/install-deps.sh
jobs=$(nproc)
# ccache (scripts/deps/robustness.txt): a developer's rebuilds, and the stages after this one,
# compile the same objects again.
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSFIT_BUILD_TESTS=ON -DSFIT_BUILD_BENCH=ON \
  "${launcher[@]}"
cmake --build build -j "$jobs"
ctest --test-dir build --output-on-failure -j "$jobs"
for stage in scripts/test.d/*.sh; do
  [ -e "$stage" ] || continue
  echo "== $stage"
  bash "$stage"
done
