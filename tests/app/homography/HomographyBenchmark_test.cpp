#include "app/homography/HomographyBenchmark.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core/utility.hpp>

#include "engine/core/Error.hpp"
#include "render/context/GlContext.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(HomographyBenchmark, BothMethodsRunOnTheSameFramesAgainstExactTruth) {
  const auto context = render::createHeadlessContext();
  cv::setNumThreads(1);
  BenchmarkOptions o;
  o.size = {320, 240};
  o.frames = 12;  // the first 12 frames of a 300-frame pan: 0.8 deg per frame, up to 9 degrees
  o.pathFrames = 300;
  const BenchmarkResult r = runHomographyBenchmark(o);
  for (const BenchmarkSide* s : {&r.tracker, &r.baseline}) {
    ASSERT_EQ(s->milliseconds.size(), 12u);
    ASSERT_EQ(s->cornerErrorPx.size(), 12u);
    for (double ms : s->milliseconds) EXPECT_GT(ms, 0.0);
  }
  EXPECT_EQ(r.tracker.registered, 12) << (r.tracker.failures.empty() ? "" : r.tracker.failures[0]);
  // Sub-pixel corner registration for reftrack (measured ~0.3 px); the ORB baseline is only
  // required to be finite where it registered.
  EXPECT_LT(finiteMedian(r.tracker.cornerErrorPx), 0.6);
  for (double e : r.baseline.cornerErrorPx) {
    if (!std::isnan(e)) {
      EXPECT_TRUE(std::isfinite(e));
    }
  }
}

TEST(HomographyBenchmark, FiniteMedianSkipsNaN) {
  EXPECT_DOUBLE_EQ(finiteMedian({3.0, NAN, 1.0, 2.0}), 2.0);
  EXPECT_TRUE(std::isnan(finiteMedian({NAN})));
  BenchmarkOptions o;
  o.frames = 0;
  EXPECT_THROW(o.check(), Error);
  o.frames = 20;
  o.pathFrames = 10;
  EXPECT_THROW(o.check(), Error);
}
