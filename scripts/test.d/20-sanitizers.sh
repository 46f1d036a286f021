#!/usr/bin/env bash
# CI stage: the whole test suite again, built with AddressSanitizer + UndefinedBehaviorSanitizer
# (preset 'asan': GCC, -O1 -g1 with assertions on, -fno-sanitize-recover=undefined), so any
# memory error, leak, failed assertion or undefined behaviour fails a test. Left to the release
# run: the tests labelled "browser" (the page's behaviour in Chromium; the server they drive is
# covered here by editor_api, editor_files and the C++ server tests) and "viewers" (files read
# by VTK and FreeCAD, written by the same code the exchange tests run here): some 3 minutes of
# the CI's 45.
# Also left to the release run: eight of the largest data cases (listed in `long` below, some
# 310 s of the sanitized run). Each repeats at a larger size a code path that smaller tests of
# the same suite run here (the geometric rule, adaptive knots, the lower bound's scan, the
# fallback below the points on 60,000 points, rotated sections, tessellation density, many
# short rows).
# Build folder: ASAN_BUILD_DIR (default build-asan).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
start=$(date +%s)
jobs=$(nproc)
dir="${ASAN_BUILD_DIR:-build-asan}"
launcher=()  # ccache where it is installed
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake --preset asan -B "$dir" "${launcher[@]}" >/dev/null
cmake --build "$dir" -j "$jobs"
built=$(date +%s)
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
if [ -f scripts/sanitizers/lsan.supp ]; then
  export LSAN_OPTIONS="suppressions=$PWD/scripts/sanitizers/lsan.supp:print_suppressions=0"
fi
long='^(GeometricRule.DefaultBeatsTheRowRulesOnScanData'
long+='|AdaptiveKnots.CorneredSectionsAndALocalBumpNeedAtLeastThirtyPercentFewer'
long+='|LowerBound.TheLinearScanIsBounded|RotatedSections.BigBladeCopiesKeepTheCountsAtFineTolerance'
long+='|Tessellate.DefaultDensityHoldsTheChordalError|Tessellate.DefaultMeshKeepsTheTriangleBudget'
long+='|Extremes.HundredThousandRowsOfThreePoints|BelowPoints.ShakyClosedSectionsGetBelowThePointsWithoutAFold)$'
ctest --test-dir "$dir" --output-on-failure -j "$jobs" -LE '^(browser|viewers)$' -E "$long"
echo "sanitizers: build $((built - start)) s, tests $(($(date +%s) - built)) s"
