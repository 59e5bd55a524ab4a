#include "app/cli/HeapReuse.hpp"

#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdlib>
#include <cstring>

namespace reftrack::app {
namespace {

// After the setting, an 8 MB block (a few float images) comes from the heap, not from a fresh
// mmap (mallinfo2's hblks counts the mmapped blocks), and when freed it stays with the process:
// allocating it again does not grow the heap (arena bytes unchanged).
TEST(HeapReuse, LargeBlocksComeFromTheHeapAndAreKeptWhenFreed) {
  ASSERT_TRUE(keepFreedMemoryForReuse());
  constexpr size_t kBytes = 8u << 20;
  const size_t mmappedBefore = mallinfo2().hblks;
  void* block = std::malloc(kBytes);
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, kBytes);  // touched, as an image buffer is
  EXPECT_EQ(mallinfo2().hblks, mmappedBefore);
  std::free(block);
  const size_t arenaAfterFree = mallinfo2().arena;
  block = std::malloc(kBytes);
  ASSERT_NE(block, nullptr);
  EXPECT_EQ(mallinfo2().arena, arenaAfterFree);
  std::free(block);
}

}  // namespace
}  // namespace reftrack::app
