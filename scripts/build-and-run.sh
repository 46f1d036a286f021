#!/usr/bin/env bash
# Installs what building sfit needs (not the test and benchmark tools), builds the CLI
# (build/apps/sfit/sfit), and fits the bundled hull example.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/install-deps.sh --build-only
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSFIT_BUILD_TESTS=OFF -DSFIT_BUILD_BENCH=OFF
cmake --build build --target sfit_cli
mkdir -p out
build/apps/sfit/sfit fit examples/ship_px121_stations.rows -o out/hull.json --report out/hull-report.json
echo "surface: out/hull.json  report: out/hull-report.json"
