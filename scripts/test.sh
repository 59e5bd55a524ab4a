#!/usr/bin/env bash
# Set up, build and run the whole CTest suite.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh" Release
build="${REFTRACK_BUILD_DIR:-$root/build}"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 900
# Under CI, each fuzz target briefly (tests/fuzz; ~15 s each) when clang can link a fuzzer; a
# finding fails the run (user YAML is checked by engine/config/YamlSubsetValidator before OpenCV's
# parser, whose hangs made findings non-fatal before).
if [ "${CI:-}" = "true" ] && bash "$root/scripts/fuzz-available.sh"; then
  bash "$root/scripts/fuzz.sh" "${REFTRACK_CI_FUZZ_SECONDS:-15}"
fi
