#!/usr/bin/env bash
# Set up, build and run the whole CTest suite.
#   test.sh                     Release build in build/ (what CI runs)
#   test.sh --sanitize          AddressSanitizer + UBSan build in build-asan/, the whole suite
#   test.sh --sanitize=thread   ThreadSanitizer build in build-tsan/, the tests of threaded parts
# (the sanitizer runs: scripts/test-sanitizers.sh)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
sanitize=""
case "${1:-}" in
  "") ;;
  --sanitize | --sanitize=address,undefined) sanitize=address,undefined ;;
  --sanitize=thread) sanitize=thread ;;
  *)
    echo "usage: test.sh [--sanitize | --sanitize=thread]" >&2
    exit 2
    ;;
esac
bash "$root/scripts/setup.sh"
if [ -n "$sanitize" ]; then
  exec bash "$root/scripts/test-sanitizers.sh" "$sanitize"
fi
bash "$root/scripts/build.sh" Release
build="${REFTRACK_BUILD_DIR:-$root/build}"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 900
# Under CI, each fuzz target briefly (tests/fuzz; ~15 s each) when clang can link a fuzzer; a
# finding fails the run (user YAML is read by yaml-cpp: engine/config/YamlTree).
if [ "${CI:-}" = "true" ] && bash "$root/scripts/fuzz-available.sh"; then
  bash "$root/scripts/fuzz.sh" "${REFTRACK_CI_FUZZ_SECONDS:-15}"
fi
