#!/usr/bin/env bash
# CI stage: build the libFuzzer targets (preset 'fuzz': clang, ASan + UBSan) and run each for
# FUZZ_SECONDS (default 30) on corpora seeded from examples/, tests/bad_input/ and STEP/IGES
# section files written by make_section_seeds. The surface seeds are fitted by the main build's
# CLI (BUILD_DIR, default build; scripts/test.sh builds it first), so this stage compiles only
# the fuzz targets with clang. Prints one summary line per target; fails if
# any target finds a crash, a hang (a unit over 10 s), a leak or a sanitizer report.
# Crashing inputs are kept in
# build-fuzz/artifacts/. Environment: FUZZ_SECONDS, FUZZ_WORK (default build-fuzz/run).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
seconds="${FUZZ_SECONDS:-30}"
work="${FUZZ_WORK:-build-fuzz/run}"
start=$(date +%s)

launcher=()  # ccache where it is installed
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake --preset fuzz "${launcher[@]}" >/dev/null
cmake --build --preset fuzz -j "$(nproc)"
bin=build-fuzz/fuzz
cli="${BUILD_DIR:-build}/apps/sfit/sfit"

# --- seed corpora ---------------------------------------------------------------------------
rm -rf "$work"
mkdir -p "$work"/{rows,fitter,surface_json,sections} build-fuzz/artifacts
sources=(tests/bad_input/*.rows examples/*.rows)
n=0
for f in "${sources[@]}"; do
  n=$((n + 1))
  head -n 80 "$f" >"$work/rows/seed$n"
  # Fitter seeds: 3 option bytes, then the first 3 rows cut to 12 points each.
  awk 'BEGIN{r=0;k=0} /^[ \t]*#/{next} /^[ \t\r]*$/{if(k>0){r++;k=0;if(r==3)exit;print ""};next} {if(k<12)print; k++}' "$f" >"$work/rows3"
  { printf '\x02\x02\x50'; cat "$work/rows3"; } >"$work/fitter/seed$n-bicubic"
  { printf '\x01\x04\x2b'; cat "$work/rows3"; } >"$work/fitter/seed$n-closed"
  { printf '\x13\x13\x00'; cat "$work/rows3"; } >"$work/fitter/seed$n-deg20-interp"
done
rm -f "$work/rows3"
# Inputs that once found a problem (fuzz/regressions/<target>-<what>): run first, kept in the corpus.
for f in fuzz/regressions/fitter-*; do cp "$f" "$work/fitter/"; done
# Surface seeds: small surfaces fitted by this build's CLI from the seeds above.
for f in tests/bad_input/good.rows "$work"/rows/*; do
  "$cli" fit "$f" -q -o "$work/surface_json/$(basename "$f").json" 2>/dev/null || true
  "$cli" fit "$f" -q --closed v --degree 2 -o "$work/surface_json/$(basename "$f")-v.json" 2>/dev/null || true
done
# Section seeds: small STEP/IGES curve files made by this build (OpenCASCADE's writers).
# (OpenCASCADE keeps some allocations to exit: no leak check for this tool.)
[ -x "$bin/make_section_seeds" ] && ASAN_OPTIONS=detect_leaks=0 "$bin/make_section_seeds" "$work/sections" >/dev/null
echo "fuzz: seeds: $(ls "$work/rows" | wc -l) rows, $(ls "$work/fitter" | wc -l) fitter, $(ls "$work/surface_json" | wc -l) surface, $(ls "$work/sections" | wc -l) sections"

# --- runs -----------------------------------------------------------------------------------
status=0
summary=()
run() {
  local target=$1 corpus=$2 dict=$3
  local log="$work/$target.log"
  local rc=0
  "$bin/$target" "$work/$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
    -dict="$dict" -print_final_stats=1 -artifact_prefix="build-fuzz/artifacts/$target-" \
    >"$log" 2>&1 || rc=$?
  local runs cov corpus_size
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  corpus_size=$(ls "$work/$corpus" | wc -l)
  local verdict="no crash"
  if [ "$rc" -ne 0 ]; then
    verdict="FOUND A PROBLEM (exit $rc), see $log and build-fuzz/artifacts/"
    status=1
    grep -E "ERROR|finding|SUMMARY|Test unit written" "$log" | head -5 || true
  fi
  summary+=("$(printf '%-18s %10s executions  coverage %5s edges  corpus %5s  %s' \
    "$target" "${runs:-?}" "${cov:-?}" "$corpus_size" "$verdict")")
}
run fuzz_rows_reader rows fuzz/rows.dict
run fuzz_fitter fitter fuzz/rows.dict
run fuzz_surface_json surface_json fuzz/surface.dict
[ -x "$bin/fuzz_section_reader" ] && run fuzz_section_reader sections fuzz/section.dict
echo "fuzz: ${seconds} s per target, $(($(date +%s) - start)) s in all"
printf 'fuzz: %s\n' "${summary[@]}"
exit $status
