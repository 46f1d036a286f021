#!/usr/bin/env bash
# Measures sfit's speed and memory and writes bench/results.md (numbers for the README).
#   bench/run.sh            Google Benchmark programs + whole-CLI runs at 10^6 and 10^7 points
# Builds Release in build-bench/. Medians of repeats; run on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/install-deps.sh >/dev/null
cmake -S . -B build-bench -G Ninja -DCMAKE_BUILD_TYPE=Release -DSFIT_BUILD_TESTS=OFF >/dev/null
cmake --build build-bench --target sfit_cli bench_fit bench_banded_lsq bench_reader bench_passes >/dev/null
out=bench/results.md
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
reps=5
{
  echo "# sfit speed ($(date -u +%Y-%m-%d), $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p'))"
  echo
  echo "Medians of $reps repetitions; real (wall) time. Load average at start: $(cut -d' ' -f1-3 /proc/loadavg)."
  echo
  for b in bench_fit bench_banded_lsq bench_reader bench_passes; do
    build-bench/bench/$b --benchmark_repetitions=$reps --benchmark_report_aggregates_only=true \
      --benchmark_format=json --benchmark_min_time=0.3 > "$tmp/$b.json" 2>/dev/null
    python3 - "$tmp/$b.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
print(f"## {sys.argv[1].split('/')[-1][:-5]}\n")
print("| benchmark | real time | CPU time | rate | counters |")
print("|---|---|---|---|---|")
for b in d["benchmarks"]:
    if b.get("aggregate_name") != "median":
        continue
    unit = b["time_unit"]
    rate = f"{b['items_per_second']/1e6:.2f} M points/s" if "items_per_second" in b else ""
    skip = {"name","run_name","run_type","repetitions","threads","aggregate_name","aggregate_unit","real_time","cpu_time","time_unit","items_per_second","bytes_per_second","family_index","per_family_instance_index","iterations","repetition_index"}
    ctr = ", ".join(f"{k}={v:g}" for k, v in b.items() if k not in skip and isinstance(v, (int, float)))
    print(f"| {b['run_name']} | {b['real_time']:.3g} {unit} | {b['cpu_time']:.3g} {unit} | {rate} | {ctr} |")
print()
PY
  done
  echo "## Whole runs of sfit fit (parse to written JSON)"
  echo
  echo "| input | points | wall (median of 3) | peak memory |"
  echo "|---|---|---|---|"
  python3 - "$tmp" <<'PY'
import math, sys
d = sys.argv[1]
def write(path, M, N):
    with open(path, "w") as f:
        for j in range(M):
            t = j / (M - 1)
            f.write("\n".join(f"{100*s:.9g} {100*t:.9g} {10*math.sin(3*s)*math.cos(2*t)+5*s*t*t+0.5*math.sin(17*s+11*t):.9g}"
                              for s in (k / (N - 1) for k in range(N))))
            f.write("\n\n")
write(f"{d}/g1m.rows", 1000, 1000)
write(f"{d}/g10m.rows", 3163, 3163)
PY
  build-bench/apps/sfit/sfit pack "$tmp/g10m.rows" -o "$tmp/g10m.srows" -q
  for input in g1m.rows g10m.srows; do
    times=()
    mem=0
    for i in 1 2 3; do
      /usr/bin/time -f "%e %M" -o "$tmp/time" build-bench/apps/sfit/sfit fit "$tmp/$input" -o "$tmp/out.json" -q
      read -r t m < "$tmp/time"
      times+=("$t")
      mem=$m
    done
    med=$(printf '%s\n' "${times[@]}" | sort -n | sed -n 2p)
    pts=$([ "$input" = g1m.rows ] && echo 1000000 || echo 10004569)
    echo "| $input | $pts | ${med} s | $((mem / 1024)) MB |"
  done
} > "$out"
cat "$out"
