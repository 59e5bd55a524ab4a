# REFTRACK_SANITIZE: a comma-separated list of GCC/Clang sanitizers (address, undefined, leak,
# thread) that instruments every target of this project (libraries, glad, ImGui backends, the
# CLI, the tests). scripts/test.sh --sanitize uses address,undefined in build-asan/ and
# --sanitize=thread uses thread in build-tsan/. Empty (the default) changes nothing.
# Any UB aborts the process (-fno-sanitize-recover), so a finding fails its test rather than
# scrolling by; -O1 with line tables keeps the instrumented suite fast enough and its stacks
# readable.
set(REFTRACK_SANITIZE "" CACHE STRING
    "Sanitizers for every project target, e.g. address,undefined or thread (empty: none)")

if(REFTRACK_SANITIZE)
  if(REFTRACK_FUZZ)
    message(FATAL_ERROR "REFTRACK_SANITIZE and REFTRACK_FUZZ are exclusive (the fuzz build "
                        "already uses address,undefined)")
  endif()
  string(REPLACE "," ";" reftrack_sanitizer_list "${REFTRACK_SANITIZE}")
  foreach(sanitizer ${reftrack_sanitizer_list})
    if(NOT sanitizer MATCHES "^(address|undefined|leak|thread)$")
      message(FATAL_ERROR "REFTRACK_SANITIZE: unknown sanitizer '${sanitizer}' "
                          "(address, undefined, leak or thread, comma-separated)")
    endif()
  endforeach()
  if("thread" IN_LIST reftrack_sanitizer_list AND ("address" IN_LIST reftrack_sanitizer_list OR
                                                   "leak" IN_LIST reftrack_sanitizer_list))
    message(FATAL_ERROR "REFTRACK_SANITIZE: thread cannot be combined with address or leak")
  endif()
  set(reftrack_sanitize_flags -fsanitize=${REFTRACK_SANITIZE} -fno-omit-frame-pointer)
  if("undefined" IN_LIST reftrack_sanitizer_list)
    list(APPEND reftrack_sanitize_flags -fno-sanitize-recover=undefined)
  endif()
  if("address" IN_LIST reftrack_sanitizer_list)
    # Eigen stops trusting glibc's 16-byte-aligned malloc under AddressSanitizer and switches to
    # its own aligned allocation (an offset stored before the block), but the uninstrumented
    # Debian libceres keeps the plain malloc path: a matrix Ceres allocates and our code frees
    # (ceres::GradientChecker::ProbeResults in the cost tests) was reported as a heap-buffer-
    # overflow 8 bytes before the block. Keep libceres's allocation scheme in our code too
    # (libceres, in the same process, already relies on that malloc being 16-byte aligned).
    add_compile_definitions(EIGEN_MALLOC_ALREADY_ALIGNED=1)
  endif()
  # After CMAKE_CXX_FLAGS_<CONFIG>, so -O1 replaces Release's -O3 (NDEBUG stays as configured).
  add_compile_options(${reftrack_sanitize_flags} -O1 -g1)
  add_link_options(-fsanitize=${REFTRACK_SANITIZE})
  message(STATUS "reftrack: sanitizers ${REFTRACK_SANITIZE}")
endif()

# After the targets exist (top-level CMakeLists.txt). The installed static libraries carry the
# instrumentation, so whatever links them (the install test's consumer, a user's project) links
# the sanitizer runtimes too. Under ThreadSanitizer, the app and its tests run OpenCV on one
# thread (tests/sanitizers/OpenCvSingleThread.cpp says why).
function(reftrack_finish_sanitizer_setup)
  if(NOT REFTRACK_SANITIZE)
    return()
  endif()
  foreach(target reftrack_engine reftrack_render)
    set_property(TARGET ${target} APPEND PROPERTY INTERFACE_LINK_OPTIONS
                 $<INSTALL_INTERFACE:-fsanitize=${REFTRACK_SANITIZE}>)
  endforeach()
  if(REFTRACK_SANITIZE MATCHES "thread")
    target_sources(reftrack_app PRIVATE ${PROJECT_SOURCE_DIR}/tests/sanitizers/OpenCvSingleThread.cpp)
  endif()
endfunction()
