#!/usr/bin/env bash
# Exits 0 when clang can link a libFuzzer target with AddressSanitizer and
# UndefinedBehaviorSanitizer here (Debian: clang-14, libclang-rt-14-dev), 1 otherwise.
set -uo pipefail
command -v clang++ >/dev/null 2>&1 || exit 1
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
printf 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }\n' \
  >"$scratch/probe.cpp"
clang++ -fsanitize=fuzzer,address,undefined "$scratch/probe.cpp" -o "$scratch/probe" \
  >/dev/null 2>&1 || exit 1
"$scratch/probe" -runs=1 >/dev/null 2>&1
