#!/usr/bin/env bash
# The sanitizer runs of the test suite (scripts/test.sh --sanitize[=thread] calls this).
#   test-sanitizers.sh address,undefined   AddressSanitizer (with LeakSanitizer) and
#       UndefinedBehaviorSanitizer, build-asan/ ($REFTRACK_ASAN_BUILD_DIR), the whole CTest suite.
#   test-sanitizers.sh thread   ThreadSanitizer, build-tsan/ ($REFTRACK_TSAN_BUILD_DIR), the tests
#       of the threaded parts (the list and why: REFTRACK_THREADED_TESTS in tests/CMakeLists.txt,
#       which builds only those tests in this configuration).
# Every sanitizer report, from a test executable or from a `reftrack` process a test starts, is
# written to <build>/sanitizer-logs/ and fails the run (a report in a child whose non-zero exit a
# test expects would otherwise pass unseen); the reports are printed at the end.
# REFTRACK_TEST_SELECTION=REGEX (test file names without _test.cpp) builds and runs only those
# tests, e.g. REFTRACK_TEST_SELECTION='PoseTracker|Relocaliser' for a quick instrumented run.
# Suppressions (third-party code only, each with its reason): tests/sanitizers/*.supp.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
sanitizers="${1:?usage: test-sanitizers.sh address,undefined|thread}"
case "$sanitizers" in
  address,undefined)
    build="${REFTRACK_ASAN_BUILD_DIR:-$root/build-asan}"
    ;;
  thread)
    build="${REFTRACK_TSAN_BUILD_DIR:-$root/build-tsan}"
    ;;
  *)
    echo "test-sanitizers.sh: unknown sanitizers '$sanitizers' (address,undefined or thread)" >&2
    exit 2
    ;;
esac

logs="$build/sanitizer-logs"
supp="$root/tests/sanitizers"
# halt_on_error: the first report ends the process, so its test fails where the error is.
# exitcode=86: a test expecting `reftrack` to exit 1 (bad input) fails when it died of a report.
# UBSan inside the ASan runtime (GCC 12) ignores log_path and prints to stderr: the test output
# (LastTest.log) is searched for reports too.
export ASAN_OPTIONS="log_path=$logs/asan:detect_leaks=1:halt_on_error=1:exitcode=86"
export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="log_path=$logs/ubsan:print_stacktrace=1:halt_on_error=1:exitcode=86"
export TSAN_OPTIONS="log_path=$logs/tsan:suppressions=$supp/tsan.supp:halt_on_error=1:second_deadlock_stack=1"
# Under ThreadSanitizer the app and its tests run OpenCV's loops on one thread (libtbb is not
# instrumented): tests/sanitizers/OpenCvSingleThread.cpp.

werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
rm -rf "$logs"
mkdir -p "$logs"  # before the build: test discovery runs the instrumented test executables
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DREFTRACK_SANITIZE="$sanitizers" \
  -DREFTRACK_WERROR="$werror" -DREFTRACK_TEST_SELECTION="${REFTRACK_TEST_SELECTION:-}" >/dev/null
cmake --build "$build" -j "$(nproc)"

start=$(date +%s)
status=0
# Instrumented code runs 2-15 times slower: a longer per-test timeout than test.sh's 900 s.
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 3600 ||
  status=$?
echo "test-sanitizers.sh: $sanitizers suite took $(($(date +%s) - start)) s"
if grep -E "runtime error:|ERROR: (Address|Leak)Sanitizer|WARNING: ThreadSanitizer" \
  "$build/Testing/Temporary/LastTest.log" >"$logs/in-test-output.txt"; then
  echo "test-sanitizers.sh: sanitizer reports in the test output ($logs/in-test-output.txt)" >&2
else
  rm -f "$logs/in-test-output.txt"
fi
reports=("$logs"/*)
if [ -e "${reports[0]}" ]; then
  for report in "${reports[@]}"; do
    echo "==== $report"
    cat "$report"
  done
  echo "test-sanitizers.sh: ${#reports[@]} sanitizer report(s) above ($logs)" >&2
  status=1
fi
exit "$status"
