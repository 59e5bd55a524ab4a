#!/usr/bin/env bash
# Set up, build and run the whole CTest suite.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh" Release
build="${REFTRACK_BUILD_DIR:-$root/build}"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 900
# Under CI, each fuzz target briefly (tests/fuzz; ~15 s each) when clang can link a fuzzer.
if [ "${CI:-}" = "true" ] && bash "$root/scripts/fuzz-available.sh"; then
  # Findings are printed (inputs in build-fuzz/artifacts/) but do not fail CI: OpenCV 4.6's YAML
  # parser still has hangs the fuzzers can hit within seconds (only some shapes are refused first,
  # engine/config/ConfigFile.cpp), and a random find must not make the suite flaky.
  bash "$root/scripts/fuzz.sh" "${REFTRACK_CI_FUZZ_SECONDS:-15}" ||
    echo "test.sh: the fuzzers reported findings (above); not failing CI for them"
fi
