#!/usr/bin/env bash
# Installs the build into a temporary prefix and builds a consumer with find_package(sfit),
# requiring and using the optional components given.
# Usage: consumer_test.sh BUILD_DIR SOURCE_DIR [COMPONENT,COMPONENT...]
set -euo pipefail
build=$1
src=$2
components=${3:-}
components=${components//,/;}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
cmake -S "$src/tests/consumer" -B "$tmp/build" -G Ninja -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  "-DSFIT_COMPONENTS=$components" >/dev/null
cmake --build "$tmp/build" >/dev/null
"$tmp/build/consumer" "$tmp"
