#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz (clang, AddressSanitizer + UndefinedBehaviorSanitizer,
# own build folder) and runs each for SECONDS (default 60; as many targets at a time as cores,
# REFTRACK_FUZZ_JOBS) from its seed corpus in
# tests/fuzz/corpus/<target>/. Prints the executions, their rate and the slowest input of the
# corpus it grew (each replayed once afterwards: ms in the instrumented build) per target; exits 1
# on any crash, hang
# (> 1 s per input) or leak, leaving the input in $build/artifacts/<target>/ and printing the end
# of the log and the input (base64) on stderr, so a CI log shows what failed.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (REFTRACK_FUZZ_BUILD_DIR, default build-fuzz;
# REFTRACK_FUZZ_RUNS=N stops each target after N executions, e.g. `REFTRACK_FUZZ_RUNS=1000000
# scripts/fuzz.sh 0 fuzz_camera_file` with no time limit; REFTRACK_FUZZ_TIMEOUT=S (default 1)
# for a machine so loaded that a process can be starved past a 1-s wall-clock alarm: inputs slower
# than 1 s are then still saved as slow-unit-* in the artifacts and counted in the result)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
shift || true
build="${REFTRACK_FUZZ_BUILD_DIR:-$root/build-fuzz}"

if ! bash "$root/scripts/fuzz-available.sh"; then
  bash "$root/scripts/setup.sh" --fuzz
fi

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Fuzz -DCMAKE_C_COMPILER=clang \
  -DCMAKE_CXX_COMPILER=clang++ -DREFTRACK_FUZZ=ON -DREFTRACK_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" --target fuzz_all -j "$(nproc)"

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for dir in "$root"/tests/fuzz/corpus/*/; do targets+=("fuzz_$(basename "$dir")"); done
fi

# One target: fuzzes it, replays its grown corpus, writes its table row to $build/$target.row and
# exits 1 when it failed.
run_target() {
  local target="$1" name corpus artifacts log result slow runs rate warmup slowest
  name="${target#fuzz_}"
  corpus="$build/corpus/$name"       # grows as the fuzzer finds new inputs; seeds stay clean
  artifacts="$build/artifacts/$name/"
  mkdir -p "$corpus" "$artifacts"
  log="$build/$target.log"
  result=ok
  local status=0
  if ! ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$build/tests/fuzz/$target" "$corpus" "$root/tests/fuzz/corpus/$name" \
    -max_total_time="$seconds" -timeout="${REFTRACK_FUZZ_TIMEOUT:-1}" -report_slow_units=1 \
    -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$artifacts" ${REFTRACK_FUZZ_RUNS:+-runs="$REFTRACK_FUZZ_RUNS"} >"$log" 2>&1; then
    result="FAILED (see $log and $artifacts)"
    status=1
  fi
  slow=$(find "$artifacts" -name 'slow-unit-*' | wc -l)
  [ "$slow" -eq 0 ] || result="$result ($slow slow unit(s) > 1 s in $artifacts: replay them)"
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  # Each input of the grown corpus once more, timed by libFuzzer ("Executed FILE in N ms"); a seed
  # runs first in each process and is not counted (the first input pays one-time set-up).
  warmup=$(find "$root/tests/fuzz/corpus/$name" -type f | sort | head -1) || true
  slowest=$(find "$corpus" -type f -print0 |
    xargs -0 -r -n 500 "$build/tests/fuzz/$target" "$warmup" 2>&1 | grep -vF "Executed $warmup " |
    sed -n 's/^Executed .* in \([0-9]*\) ms$/\1/p' | sort -n | tail -1) || true
  printf '%-26s %12s %10s %11s %s\n' "$target" "${runs:-?}" "${rate:-?}" "${slowest:-?}" "$result" \
    >"$build/$target.row"
  return "$status"
}

# As many targets at a time as there are cores (REFTRACK_FUZZ_JOBS): each fuzzer is one process,
# so on 2 cores the ten targets take half the wall time for the same seconds each.
jobs_max="${REFTRACK_FUZZ_JOBS:-$(nproc)}"
for target in "${targets[@]}"; do
  rm -f "$build/$target.row"
  while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do wait -n || true; done
  run_target "$target" &
done
wait || true

failed=()
printf '%-26s %12s %10s %11s %s\n' target executions exec/s slowest/ms result
for target in "${targets[@]}"; do
  if [ -f "$build/$target.row" ]; then
    cat "$build/$target.row"
    grep -q ' FAILED ' "$build/$target.row" && failed+=("$target")
  else
    printf '%-26s %12s %10s %11s %s\n' "$target" ? ? ? "FAILED (no result: see $build/$target.log)"
    failed+=("$target")
  fi
done

if [ ${#failed[@]} -ne 0 ]; then
  # The report of each failure where CI shows it (the logs stay in the build folder).
  for target in "${failed[@]}"; do
    echo "---- $target: the end of $build/$target.log" >&2
    grep -v -E '^#[0-9]+[[:space:]]+(NEW|REDUCE|pulse|INITED)' "$build/$target.log" | tail -n 40 >&2
    for input in "$build/artifacts/${target#fuzz_}"/*; do
      [ -f "$input" ] || continue
      echo "---- $target: the input $input (first 2 kB, base64)" >&2
      head -c 2048 "$input" | base64 >&2
    done
  done
  echo "fuzz: ${#failed[@]} target(s) failed: ${failed[*]}" >&2
  exit 1
fi
