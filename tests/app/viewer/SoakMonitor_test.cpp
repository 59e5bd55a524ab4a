#include "app/viewer/SoakMonitor.hpp"

#include <gtest/gtest.h>
#include <sys/mman.h>

#include <sstream>
#include <vector>

#include "engine/core/Error.hpp"

namespace reftrack::app {
namespace {

TEST(SoakMonitor, ResidentMemoryGrowsWhenThisProcessTouchesMemory) {
  const std::optional<double> before = residentMemoryMiB();
  ASSERT_TRUE(before.has_value()) << "/proc/self/statm unreadable";
  EXPECT_GT(*before, 1.0);  // a gtest binary linked against OpenCV is far above 1 MiB
  // 64 MiB of fresh pages written page by page must show up as resident (16 MiB of slack). Mapped
  // here, not allocated: after other tests in this process freed frames, malloc served the block
  // from heap memory that was resident already (403.7 -> 403.7 MiB).
  const std::size_t bytes = 64u << 20;
  void* mapped = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(mapped, MAP_FAILED);
  char* block = static_cast<char*>(mapped);
  for (std::size_t i = 0; i < bytes; i += 4096) block[i] = static_cast<char>(i);
  const double after = residentMemoryMiB().value();
  EXPECT_GT(after - *before, 48.0) << before.value() << " -> " << after;
  munmap(mapped, bytes);
}

TEST(SoakMonitor, SamplesEveryIntervalAndComparesAgainstTheFirstIntervalAfterWarmup) {
  std::ostringstream out;
  // Clocks the test drives: each frame takes 2 ms of wall time and 1.5 ms of CPU, the last
  // interval's frames twice that (a slowdown the monitor must report).
  double wall = 100.0, cpu = 7.0;
  SoakMonitor monitor(10, 20, &out, {[&] { return wall; }, [&] { return cpu; }});
  for (int i = 0; i < 60; ++i) {
    wall += i >= 50 ? 0.004 : 0.002;
    cpu += i >= 50 ? 0.003 : 0.0015;
    monitor.frameDone();
  }
  const SoakSummary s = monitor.summary();
  ASSERT_EQ(s.samples.size(), 6u);
  EXPECT_EQ(s.samples.front().frames, 10);
  EXPECT_EQ(s.samples.back().frames, 60);
  ASSERT_TRUE(s.complete);
  // The first interval wholly after the 20-frame warm-up is frames 20..30.
  EXPECT_DOUBLE_EQ(s.firstRate, s.samples[2].framesPerSecond);
  EXPECT_DOUBLE_EQ(s.lastRate, s.samples[5].framesPerSecond);
  EXPECT_NEAR(s.firstRate, 500.0, 1e-6);  // 10 frames in 20 ms
  EXPECT_NEAR(s.lastRate, 250.0, 1e-6);
  EXPECT_NEAR(s.rateRatio, 0.5, 1e-9);
  EXPECT_NEAR(s.firstCpuMs, 1.5, 1e-9);
  EXPECT_NEAR(s.lastCpuMs, 3.0, 1e-9);
  EXPECT_NEAR(s.cpuRatio, 2.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.growthMiB, s.residentEndMiB - s.residentAfterWarmupMiB);
  EXPECT_NE(out.str().find("(warm-up)"), std::string::npos);
  std::ostringstream summary;
  printSoakSummary(summary, s);
  EXPECT_NE(summary.str().find("growth"), std::string::npos);
}

TEST(SoakMonitor, TooShortARunGivesNoVerdict) {
  SoakMonitor monitor(10, 1000, nullptr);
  for (int i = 0; i < 30; ++i) monitor.frameDone();
  EXPECT_FALSE(monitor.summary().complete);
  std::ostringstream out;
  printSoakSummary(out, monitor.summary());
  EXPECT_NE(out.str().find("too few frames"), std::string::npos);
}

TEST(SoakMonitor, RejectsABadInterval) {
  EXPECT_THROW(SoakMonitor(0, 0, nullptr), Error);
  EXPECT_THROW(SoakMonitor(10, -1, nullptr), Error);
}

}  // namespace
}  // namespace reftrack::app
