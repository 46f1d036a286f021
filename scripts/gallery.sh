#!/usr/bin/env bash
# Makes the picture gallery of docs/pictures.md, docs/gallery/*.png, from data sets in
# examples/: blade, ring body, hull and terrain, each fitted once with 'sfit fit' and drawn in
# the shaded, zebra and deviation modes (the deviations are the fit report's own), plus one
# row picture.
#
# Usage: scripts/gallery.sh [BUILD_DIR]     (default: build; configured and built if needed)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build="${1:-build}"
sfit="$build/apps/sfit/sfit"
if [ ! -x "$sfit" ] || ! "$sfit" render --help >/dev/null 2>&1; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSFIT_BUILD_RENDER=ON
  cmake --build "$build" -j "$(nproc)" --target sfit_cli
fi
out=docs/gallery
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"

# find NAME: the data set in examples/, else nothing.
find_data() {
  if [ -f "examples/$1" ]; then echo "examples/$1"; fi
}

# picture NAME FILE FIT_OPTIONS... -- PICTURE_OPTIONS...
picture() {
  local name="$1" file="$2"
  shift 2
  local fit=() pic=()
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do fit+=("$1"); shift; done
  [ $# -gt 0 ] && shift
  pic=("$@")
  if [ -z "$file" ]; then
    echo "gallery: $name: data set not found, skipped" >&2
    return
  fi
  "$sfit" fit "$file" "${fit[@]}" -o "$tmp/$name.json" \
    --png "$out/$name-shaded.png" --png "$out/$name-zebra.png" --png "$out/$name-deviation.png" \
    --mode shaded --mode zebra --mode deviation "${pic[@]}"
}

picture blade "$(find_data iea3p4mw_blade_ragged9.rows)" --closed u -- --up x --view 200,30
picture body "$(find_data ring_body.rows)" --closed u -- --view 30,30
picture hull "$(find_data ship_px121_stations.rows)" -- --view 150,20 --stripes 10
picture terrain "$(find_data height_field.rows)" --tol 3 -- --exaggerate 2 --view 210,35 --stripes 8

blade="$(find_data iea3p4mw_blade_ragged9.rows)"
"$sfit" render-rows "$blade" --row 4 --closed u --size 800x600 -o "$out/blade-row4.png"
ls -l "$out"
