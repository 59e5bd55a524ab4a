#pragma once
// HeapReuse: the process keeps the memory it frees for its next allocations instead of giving
// large blocks back to the kernel at once (glibc's mallopt). Image work allocates and frees the
// same multi-megabyte buffers every frame (SIFT's scale space, pyramids); returned to the kernel,
// each is faulted in again page by page.

namespace reftrack::app {

// Large blocks (up to 32 MB) come from the heap, and up to 256 MB of free heap is kept. Returns
// false when the C library refused a setting (the process then runs with its defaults).
bool keepFreedMemoryForReuse();

}  // namespace reftrack::app
