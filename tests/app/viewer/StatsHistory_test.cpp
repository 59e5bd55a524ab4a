// StatsHistory: bounded history, mean loop rate, pose and overlay-error series with gaps.
#include "app/viewer/StatsHistory.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(StatsHistory, KeepsTheLastFramesAndComputesSeries) {
  StatsHistory h(3);
  for (int k = 0; k < 5; ++k) {
    FrameStats s;
    s.index = k;
    s.loopMilliseconds = k == 0 ? 0.0 : 40.0;
    s.inliers = 10 * k;
    if (k != 3) {
      Vector6d v;
      v << k, 0, 0, 0, 0, -k;
      s.pose = v;
    }
    h.add(s);
  }
  ASSERT_EQ(h.frames().size(), 3u);
  EXPECT_EQ(h.frames().front().index, 2);
  EXPECT_DOUBLE_EQ(h.meanFps(), 25.0);  // 40 ms per frame
  const auto tx = h.poseSeries(0), rz = h.poseSeries(5);
  EXPECT_FLOAT_EQ(tx[0], 2.0f);
  EXPECT_TRUE(std::isnan(tx[1]));  // frame 3 had no pose
  EXPECT_FLOAT_EQ(rz[2], -4.0f);
  EXPECT_EQ(h.inlierSeries(), (std::vector<float>{20, 30, 40}));
  EXPECT_THROW(h.poseSeries(6), Error);
  EXPECT_THROW(StatsHistory(0), Error);
  h.clear();
  EXPECT_DOUBLE_EQ(h.meanFps(), 0.0);
}

TEST(StatsHistory, OverlayErrorSeriesHaveGapsWhereThereIsNoFigure) {
  StatsHistory h(4);
  EXPECT_FALSE(h.groundTruthLoaded());
  h.setGroundTruthLoaded(true);
  EXPECT_TRUE(h.groundTruthLoaded());
  for (int k = 0; k < 4; ++k) {
    FrameStats s;
    s.index = k;
    if (k != 1) s.predictedErrorPx = 0.5 * k;
    if (k == 2) s.trueErrorPx = 0.75;
    h.add(s);
  }
  const std::vector<float> predicted = h.predictedErrorSeries(), measured = h.trueErrorSeries();
  ASSERT_EQ(predicted.size(), 4u);
  EXPECT_FLOAT_EQ(predicted[0], 0.0f);
  EXPECT_TRUE(std::isnan(predicted[1]));
  EXPECT_FLOAT_EQ(predicted[3], 1.5f);
  ASSERT_EQ(measured.size(), 4u);
  EXPECT_TRUE(std::isnan(measured[0]));
  EXPECT_FLOAT_EQ(measured[2], 0.75f);
}
