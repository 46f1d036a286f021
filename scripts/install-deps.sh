#!/usr/bin/env bash
# Installs every Debian package sfit needs to build, test and benchmark.
# Usage: scripts/install-deps.sh [--build-only]   (run as root, or with sudo available)
#   --build-only   only what building and running sfit needs (scripts/deps/build.txt)
# The package lists live in scripts/deps/*.txt, one package per line, one file per area,
# so each part of the project states what it needs and why.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
lists=("$here"/deps/*.txt)
case "${1:-}" in
  --build-only) lists=("$here/deps/build.txt") ;;
  "") ;;
  *) echo "usage: scripts/install-deps.sh [--build-only]" >&2; exit 2 ;;
esac
mapfile -t pkgs < <(cat "${lists[@]}" | sed -e 's/#.*//' -e 's/[[:space:]]//g' | grep -v '^$' | sort -u)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
# The editor's page and tests: three.js and puppeteer-core from editor/package-lock.json
# (puppeteer-core downloads no browser: the tests use Debian's chromium). Debian's nodejs
# comes without npm (package npm); nodejs builds that bundle npm conflict with that package.
npm_ci() {
  [ -f "$here/../editor/package-lock.json" ] || return 0
  if ! command -v npm >/dev/null 2>&1 && command -v apt-get >/dev/null 2>&1; then
    ${SUDO:-} apt-get install -y -qq --no-install-recommends npm
  fi
  local dir="$here/../editor"
  # Up to date when the last npm ci was of this very lock file.
  cmp -s "$dir/package-lock.json" "$dir/node_modules/.sfit-installed-lock" && return 0
  (cd "$dir" && npm ci --no-audit --no-fund --loglevel=error &&
    cp package-lock.json node_modules/.sfit-installed-lock)
}
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#pkgs[@]} packages present"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  npm_ci
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
npm_ci
