#!/usr/bin/env bash
# Every C++ file git tracks is as .clang-format writes it (clang-format --dry-run --Werror).
#   scripts/check_format.sh [CLANG_FORMAT]     exit 0 when all are, 1 naming each one that is not
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
cf=${1:-clang-format}
out=$(git ls-files -z '*.cpp' '*.h' | xargs -0 "$cf" --dry-run --Werror 2>&1) && exit 0
# clang-format names each file and line it would change: one line per file here.
grep -o '^[^:]*\.\(cpp\|h\):' <<< "$out" | sort -u | sed 's/:$/: not formatted (clang-format -i)/'
exit 1
