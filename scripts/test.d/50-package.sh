#!/usr/bin/env bash
# CI stage: the optional parts degrade, and the Debian package works.
#  1. A configure that finds neither OpenCASCADE nor libpng (CMAKE_DISABLE_FIND_PACKAGE_*)
#     builds the CLI: meshes and VTK files are written, STEP is refused with a usage error
#     (exit 2), there is no 'render' command. Folder build-minimal/.
#  2. A shared-library build (BUILD_SHARED_LIBS=ON) packed by CPack into a .deb, extracted
#     into a temporary root (dpkg-deb -x; the system is not touched), and a consumer built
#     against it with find_package(sfit COMPONENTS render exchange) runs, as does the packaged
#     CLI. Folder build-package/.
# Uses ccache when it is there (the objects are the ones the main build made).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
jobs=$(nproc)
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "package: FAILED: $*" >&2; exit 1; }

# --- 1. without OpenCASCADE and libpng --------------------------------------------------------
cmake -S . -B build-minimal -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
  -DSFIT_BUILD_TESTS=OFF -DSFIT_BUILD_BENCH=OFF \
  -DCMAKE_DISABLE_FIND_PACKAGE_OpenCASCADE=ON -DCMAKE_DISABLE_FIND_PACKAGE_PNG=ON >"$tmp/minimal.log"
grep -q 'sfit [0-9.]*: core, io, CLI, mesh, exchange$' "$tmp/minimal.log" ||
  fail "the minimal configure does not say what is on: $(grep 'sfit' "$tmp/minimal.log")"
grep -q 'OpenCASCADE not found: STEP/IGES off' "$tmp/minimal.log" || fail "no STEP/IGES message"
grep -q 'libpng not found: pictures' "$tmp/minimal.log" || fail "no pictures message"
cmake --build build-minimal -j "$jobs" --target sfit_cli >/dev/null
cli=build-minimal/apps/sfit/sfit
"$cli" fit examples/ship_px121_stations.rows -q -o "$tmp/hull.json" -o "$tmp/hull.stl" -o "$tmp/hull.vts"
[ -s "$tmp/hull.stl" ] && [ -s "$tmp/hull.vts" ] || fail "the minimal CLI wrote no meshes"
set +e
"$cli" convert "$tmp/hull.json" -o "$tmp/hull.step" 2>"$tmp/err"
code=$?
set -e
[ "$code" -eq 2 ] || fail "STEP without OpenCASCADE: exit $code, expected 2"
grep -q 'needs the CAD part (OpenCASCADE), which this build of sfit lacks' "$tmp/err" || fail "STEP without OpenCASCADE: $(cat "$tmp/err")"
[ ! -e "$tmp/hull.step" ] || fail "a STEP file was written without OpenCASCADE"
help=$("$cli" --help)
if grep -q '^ *render ' <<<"$help"; then fail "'render' exists without libpng"; fi
echo "package: minimal build: meshes written, STEP refused (exit 2), no pictures"

# --- 2. shared libraries, the .deb, a consumer ------------------------------------------------
cmake -S . -B build-package -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
  -DSFIT_BUILD_TESTS=OFF -DSFIT_BUILD_BENCH=OFF -DBUILD_SHARED_LIBS=ON >/dev/null
cmake --build build-package -j "$jobs" >/dev/null
rm -f build-package/sfit_*.deb
(cd build-package && cpack -G DEB >/dev/null)
deb=$(ls build-package/sfit_*.deb)
depends=$(dpkg-deb --field "$deb" Depends)
[[ "$depends" == *libeigen3-dev* ]] || fail "$deb: Depends lacks libeigen3-dev: $depends"
dpkg-deb -x "$deb" "$tmp/root"
for f in usr/bin/sfit usr/include/sfit/version.h usr/include/sfit/surface_fit.h \
         usr/include/sfit/render/image.h usr/include/sfit/exchange/writers.h \
         usr/lib/cmake/sfit/sfitConfig.cmake usr/lib/libsfit.so usr/lib/libsfit_exchange.so \
         usr/lib/sfit/libsfit_cad.so; do
  [ -e "$tmp/root/$f" ] || fail "$deb lacks $f"
done
version=$("$tmp/root/usr/bin/sfit" --version)
[[ "$version" == "sfit "* ]] || fail "the packaged CLI does not run: $version"
LD_DEBUG=files "$tmp/root/usr/bin/sfit" fit examples/d150_wing.rows --closed u -q \
  -o "$tmp/wing.igs" 2>"$tmp/loaded" || fail "the packaged CLI cannot fit: $(tail -3 "$tmp/loaded")"
# IGES through the packaged CAD module (found from usr/bin/../lib/sfit), not the build tree's.
grep -q "calling init: $tmp/root/usr/lib/sfit/libsfit_cad.so" "$tmp/loaded" ||
  fail "the packaged CLI did not load the packaged CAD module: $(grep libsfit_cad "$tmp/loaded")"
cmake -S tests/consumer -B "$tmp/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$tmp/root/usr" \
  "-DSFIT_COMPONENTS=render;exchange" >/dev/null
cmake --build "$tmp/consumer" >/dev/null
LD_LIBRARY_PATH="$tmp/root/usr/lib" "$tmp/consumer/consumer" "$tmp"
echo "package: $(basename "$deb"): $(dpkg-deb -c "$deb" | wc -l) entries; consumer and CLI run"
