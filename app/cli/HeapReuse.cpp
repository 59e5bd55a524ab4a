#include "app/cli/HeapReuse.hpp"

#include <malloc.h>

namespace reftrack::app {

// glibc serves a block above its mmap threshold (128 KB, raised by each freed block up to 32 MB)
// with a fresh mmap and trims the heap's free top above twice that: a relocalisation attempt's
// SIFT buffers (~2.4 MB per float image at 896x672) came back zeroed from the kernel on every
// attempt. Measured with `scripts/bench-relocalisation.sh --threads 1` (640x480, perf): a quarter
// of the attempt's CPU in the kernel's page faults; with these settings the median attempt took
// 27-29 ms of CPU instead of 40, the poses byte for byte the same. Setting either value turns
// glibc's dynamic threshold off, so both are set.
bool keepFreedMemoryForReuse() {
  constexpr int kMmapThreshold = 32 * 1024 * 1024;   // glibc's upper limit on 64-bit
  constexpr int kTrimThreshold = 256 * 1024 * 1024;  // free heap kept before trimming
  const bool mmap = mallopt(M_MMAP_THRESHOLD, kMmapThreshold) == 1;
  const bool trim = mallopt(M_TRIM_THRESHOLD, kTrimThreshold) == 1;
  return mmap && trim;
}

}  // namespace reftrack::app
