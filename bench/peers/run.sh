#!/usr/bin/env bash
# The peer benchmark in one command: installs what it needs, builds sfit_peers in build-peers/
# (-DSFIT_BUILD_PEERS=ON, Release), runs every tool on every data set and tolerance, and writes
# build-peers/peers/{table.md,results.json,time_vs_points.png}.
# Usage: bench/peers/run.sh [run_peers.py options, e.g. --max-points 1e6 --cap 60]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$root"
scripts/install-deps.sh
cmake -S . -B build-peers -G Ninja -DCMAKE_BUILD_TYPE=Release -DSFIT_BUILD_PEERS=ON \
  -DSFIT_BUILD_TESTS=OFF -DSFIT_BUILD_EXCHANGE=OFF -DSFIT_BUILD_RENDER=OFF -DSFIT_INSTALL=OFF
cmake --build build-peers --target sfit_peers -j 2
# Debian's python3 (where python3-scipy/numpy/matplotlib live), not a python3 earlier on PATH.
py=/usr/bin/python3
[ -x "$py" ] || py=python3
echo "run_peers: $(date -u +%FT%TZ), load $(cut -d' ' -f1-3 /proc/loadavg), commit $(git rev-parse --short HEAD)"
exec "$py" bench/peers/run_peers.py --python "$py" --bin build-peers/bench/peers/sfit_peers \
  --out build-peers/peers "$@"
