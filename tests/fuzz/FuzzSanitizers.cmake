# REFTRACK_FUZZ: every project target is compiled with libFuzzer's coverage instrumentation and
# AddressSanitizer + UndefinedBehaviorSanitizer (any UB aborts, so the fuzzer reports it); the
# targets in tests/fuzz link libFuzzer's driver. Needs clang (Debian: clang-14,
# libclang-rt-14-dev); scripts/fuzz.sh configures a separate build-fuzz/ with it.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "REFTRACK_FUZZ=ON needs clang (libFuzzer): configure with "
                      "-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang, or run scripts/fuzz.sh")
endif()
set(REFTRACK_SANITIZERS address,undefined)
# -O1 with line tables: libFuzzer's recommended trade between speed and readable stacks.
add_compile_options(-fsanitize=fuzzer-no-link,${REFTRACK_SANITIZERS}
                    -fno-sanitize-recover=undefined -fno-omit-frame-pointer -O1
                    -gline-tables-only)
add_link_options(-fsanitize=${REFTRACK_SANITIZERS})
