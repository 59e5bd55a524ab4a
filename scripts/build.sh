#!/usr/bin/env bash
# Configures and builds reftrack into build/ (or $REFTRACK_BUILD_DIR).
# Usage: build.sh [Release|Debug] [TARGET...]   (no target: everything, tests included;
# e.g. `build.sh Release reftrack` builds the CLI and its libraries only, as demo.sh does)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${REFTRACK_BUILD_DIR:-$root/build}"
type="${1:-Release}"
shift || true
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE="$type" -DREFTRACK_WERROR="$werror" >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$build" -j "$(nproc)" "${targets[@]}"
