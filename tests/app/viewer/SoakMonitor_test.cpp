#include "app/viewer/SoakMonitor.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <thread>
#include <vector>

#include "engine/core/Error.hpp"

namespace reftrack::app {
namespace {

TEST(SoakMonitor, ResidentMemoryGrowsWhenThisProcessTouchesMemory) {
  const std::optional<double> before = residentMemoryMiB();
  ASSERT_TRUE(before.has_value()) << "/proc/self/statm unreadable";
  EXPECT_GT(*before, 1.0);  // a gtest binary linked against OpenCV is far above 1 MiB
  // 64 MiB written page by page must show up as resident (allow the allocator 16 MiB of slack).
  std::vector<char> block(64u << 20);
  for (std::size_t i = 0; i < block.size(); i += 4096) block[i] = static_cast<char>(i);
  const double after = residentMemoryMiB().value();
  EXPECT_GT(after - *before, 48.0) << before.value() << " -> " << after;
  EXPECT_NE(block[4096], 1);  // keep the block alive
}

TEST(SoakMonitor, SamplesEveryIntervalAndComparesAgainstTheFirstIntervalAfterWarmup) {
  std::ostringstream out;
  SoakMonitor monitor(10, 20, &out);
  for (int i = 0; i < 60; ++i) {
    // The last interval runs about twice as slow as the earlier ones.
    std::this_thread::sleep_for(std::chrono::milliseconds(i >= 50 ? 4 : 2));
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
  // Sleeps are lower bounds, so only the direction is certain: 2 ms vs 4 ms per frame.
  EXPECT_LT(s.rateRatio, 0.95);
  EXPECT_GT(s.firstRate, 0.0);
  EXPECT_LE(s.firstRate, 1000.0 / 2.0 + 1e-9);
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
