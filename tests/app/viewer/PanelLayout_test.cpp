// PanelLayout: two panel columns and the letterboxed video between them, in GL coordinates.
#include "app/viewer/PanelLayout.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(PanelLayout, ColumnsFrameTheVideo) {
  const PanelLayout l = panelLayout({1280, 720});
  EXPECT_EQ(l.source.x, 0.0f);
  EXPECT_EQ(l.tracking.y, l.source.y + l.source.height);
  EXPECT_EQ(l.record.y + l.record.height, 720.0f);
  EXPECT_EQ(l.overlay.x + l.overlay.width, 1280.0f);
  EXPECT_EQ(l.stats.y + l.stats.height, 720.0f);
  EXPECT_EQ(l.videoArea.x, static_cast<int>(l.source.width));
  EXPECT_EQ(l.videoArea.x + l.videoArea.width, static_cast<int>(l.overlay.x));
  EXPECT_THROW(panelLayout({640, 480}), Error);
}

TEST(PanelLayout, VideoViewportIsLetterboxedInTheArea) {
  // 4:3 video in a 620x720 area at x = 330: full width, centred vertically.
  const render::Viewport v = videoViewport({640, 480}, {330, 0, 620, 720}, {1280, 720});
  EXPECT_EQ(v.x, 330);
  EXPECT_EQ(v.width, 620);
  EXPECT_EQ(v.height, 465);
  EXPECT_NEAR(v.y, (720 - 465) / 2, 1);
  // An area at the top of the canvas maps to the top of the GL framebuffer (origin bottom-left).
  const render::Viewport top = videoViewport({100, 100}, {0, 0, 100, 100}, {100, 300});
  EXPECT_EQ(top.y, 200);
}

TEST(PanelLayout, CalibrationTakesTheRightColumnAboveStats) {
  const PanelLayout plain = panelLayout({1280, 720});
  EXPECT_TRUE(plain.calibration.empty());
  const PanelLayout l = panelLayout({1280, 720}, true);
  EXPECT_EQ(l.calibration.x, 1280.0f - l.calibration.width);
  EXPECT_EQ(l.calibration.y, 0.0f);
  EXPECT_EQ(l.stats.y, l.calibration.y + l.calibration.height);
  EXPECT_EQ(l.stats.y + l.stats.height, 720.0f);
  // Overlay shares the left column with Tracking, between Source and Record, without overlap.
  EXPECT_EQ(l.overlay.x, 0.0f);
  EXPECT_EQ(l.tracking.y + l.tracking.height, l.overlay.y);
  EXPECT_EQ(l.overlay.y + l.overlay.height, l.record.y);
  EXPECT_EQ(l.videoArea, plain.videoArea);
}

TEST(PanelLayout, ReferencesSitAboveStatsInTheRightColumn) {
  const PanelLayout plain = panelLayout({1280, 720});
  EXPECT_TRUE(plain.references.empty());
  for (const bool calibration : {false, true}) {
    const PanelLayout l = panelLayout({1280, 720}, calibration, true);
    const cv::Rect2f& above = calibration ? l.calibration : l.overlay;
    EXPECT_EQ(l.references.x, 1280.0f - l.references.width) << calibration;
    EXPECT_EQ(l.references.y, above.y + above.height) << calibration;
    EXPECT_EQ(l.stats.y, l.references.y + l.references.height) << calibration;
    EXPECT_EQ(l.stats.y + l.stats.height, 720.0f) << calibration;
    EXPECT_GT(l.stats.height, 100.0f) << calibration;
    EXPECT_GT(above.height, 100.0f) << calibration;
    EXPECT_EQ(l.videoArea, plain.videoArea);
  }
}
