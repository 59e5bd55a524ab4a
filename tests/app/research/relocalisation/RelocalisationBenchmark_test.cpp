#include "app/research/relocalisation/RelocalisationBenchmark.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <opencv2/core/utility.hpp>

#include "engine/core/Error.hpp"
#include "engine/relocalisation/RelocalisationTestScene.hpp"

namespace reftrack::app {
namespace {

// Both sides run on every frame and are scored against the exact poses; frames without truth
// are timed, not scored; the printed table holds both rows and the ratio.
TEST(RelocalisationBenchmark, TimesAndScoresBothSidesOnTheSameFrames) {
  cv::setNumThreads(1);
  const test::CornerWorld world;
  const MultiReferenceMap map = test::cornerWorldMap(world, 4, RelocalisationParams{});
  const std::vector<RigidPose> views = test::randomViews(6, 4, 9);
  std::vector<cv::Mat> frames;
  std::vector<std::optional<RigidPose>> truth;
  for (std::size_t i = 0; i < views.size(); ++i) {
    frames.push_back(world.render(views[i], 70 + static_cast<int>(i)));
    truth.emplace_back(views[i]);
  }
  frames.push_back(cv::Mat::zeros(world.size, CV_8U));  // timed, no truth
  truth.emplace_back(std::nullopt);
  const RelocalisationBenchmarkResult r = runRelocalisationBenchmark(map, frames, truth);
  for (const RelocalisationBenchmarkSide* s : {&r.relocaliser, &r.baseline}) {
    EXPECT_EQ(s->attempts, 7) << s->name;
    EXPECT_EQ(s->milliseconds.size(), 7u) << s->name;
    ASSERT_EQ(s->cpuMilliseconds.size(), 7u) << s->name;
    // The thread's CPU time of an attempt is never more than its wall time (+ clock rounding).
    for (std::size_t i = 0; i < 7; ++i) {
      EXPECT_GE(s->cpuMilliseconds[i], 0.0) << s->name;
      EXPECT_LE(s->cpuMilliseconds[i], s->milliseconds[i] + 0.1) << s->name;
    }
    EXPECT_EQ(s->centreErrorMm.size(), static_cast<std::size_t>(s->found)) << s->name;
    EXPECT_LE(s->found, 6) << s->name;
  }
  EXPECT_GE(r.relocaliser.found, 5);
  EXPECT_EQ(r.relocaliser.wrong, 0);
  EXPECT_GT(r.medianMsRatio, 0.0);
  EXPECT_GT(r.medianCpuMsRatio, 0.0);
  std::printf("relocalisation benchmark (6 views of the synthetic corner + a black frame):\n");
  printRelocalisationBenchmark(r, stdout);

  EXPECT_THROW(runRelocalisationBenchmark(map, frames, {}), Error);
}

}  // namespace
}  // namespace reftrack::app
