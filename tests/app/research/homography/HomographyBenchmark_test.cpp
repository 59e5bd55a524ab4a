#include "app/research/homography/HomographyBenchmark.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
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
  for (const BenchmarkSide* s : {&r.tracker, &r.baseline, &r.calibratedTracker}) {
    ASSERT_EQ(s->milliseconds.size(), 12u);
    ASSERT_EQ(s->cornerErrorPx.size(), 12u);
    for (double ms : s->milliseconds) EXPECT_GT(ms, 0.0);
  }
  EXPECT_EQ(r.tracker.registered, 12) << (r.tracker.failures.empty() ? "" : r.tracker.failures[0]);
  // Sub-pixel corner registration for reftrack (measured ~0.3 px); the ORB baseline is only
  // required to be finite where it registered.
  EXPECT_LT(finiteMedian(r.tracker.cornerErrorPx), 0.6);
  // Given K, the rotation-only model may only replace a general fit that rests on a thin strip
  // of the reference, so here (wide overlap) it changes nothing: every frame registered, no
  // less accurate (measured: the same 0.418 px median over 150 frames).
  EXPECT_EQ(r.calibratedTracker.registered, 12);
  EXPECT_LE(finiteMedian(r.calibratedTracker.cornerErrorPx), finiteMedian(r.tracker.cornerErrorPx));
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

TEST(HomographyBenchmark, KeepsEveryFrameThroughAWidePanAt320x240) {
  const auto context = render::createHeadlessContext();
  cv::setNumThreads(1);
  BenchmarkOptions o;
  o.size = {320, 240};
  o.frames = 60;  // the bench-homography pan: out to 40 degrees (frame 37) and back to 30
  o.pathFrames = 150;
  const BenchmarkResult r = runHomographyBenchmark(o);
  // Measured 60 of 60 (the baseline: 44 of 60). Beyond ~30 degrees only 27-31 of the 55
  // reference corners are in view; a frame flagged lost there is still matched guided by the
  // carried-on prediction, so tracking does not hinge on unguided re-acquisition at 40 degrees.
  EXPECT_EQ(r.tracker.registered, 60) << (r.tracker.failures.empty() ? "" : r.tracker.failures[0]);
  EXPECT_GE(r.tracker.registered, r.baseline.registered);
  // At the frame corners, extrapolated from the strip of overlap (half of these frames are
  // beyond 25 degrees): measured median 1.13 px, worst 6.7 px (the frame corner furthest from
  // the matched strip at 40 degrees); the baseline's median 1.55 px on the 44 it registers.
  EXPECT_LT(finiteMedian(r.tracker.cornerErrorPx), 1.5);
  EXPECT_LE(finiteMedian(r.tracker.cornerErrorPx), finiteMedian(r.baseline.cornerErrorPx));
  std::printf("wide pan 320x240: reftrack %d/60 median %.3f px; ORB %d/60 median %.3f px\n",
              r.tracker.registered, finiteMedian(r.tracker.cornerErrorPx), r.baseline.registered,
              finiteMedian(r.baseline.cornerErrorPx));
}
