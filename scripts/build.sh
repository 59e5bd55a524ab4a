#!/usr/bin/env bash
# Configures and builds reftrack into build/ (or $REFTRACK_BUILD_DIR). Usage: build.sh [Release|Debug]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${REFTRACK_BUILD_DIR:-$root/build}"
type="${1:-Release}"
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE="$type" -DREFTRACK_WERROR="$werror" >/dev/null
cmake --build "$build" -j "$(nproc)"
