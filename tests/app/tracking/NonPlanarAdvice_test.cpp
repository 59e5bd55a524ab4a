#include "app/tracking/NonPlanarAdvice.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/videoio.hpp>

#include "TestPaths.hpp"
#include "engine/config/TrackerParams.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

HomographyTrackResult outcome(bool tracked, const std::string& failure = {}) {
  HomographyTrackResult r;
  r.tracked = tracked;
  r.failure = failure;
  return r;
}

}  // namespace

TEST(NonPlanarAdvice, SpeaksOnlyWhenMostRecentFramesAreRefusedRegistrations) {
  NonPlanarAdvice advice;
  // Lost frames with nothing registered at all (a covered lens, another scene): no advice.
  for (int i = 0; i < NonPlanarAdvice::kWindow; ++i)
    advice.add(outcome(false, "cold: keypoints: only 3 keypoint inliers"));
  EXPECT_FALSE(advice.advice());
  // Registrations refused by the check among the lost frames: the advice, once enough are.
  for (int i = 0; i < NonPlanarAdvice::kMinRefused - 1; ++i)
    advice.add(outcome(false, "cold: refused by the registration check: ..."));
  EXPECT_FALSE(advice.advice());
  advice.add(outcome(false, "cold: refused by the registration check: ..."));
  ASSERT_TRUE(advice.advice());
  EXPECT_NE(advice.advice()->find("one flat surface"), std::string::npos);
  EXPECT_TRUE(advice.everShown());
  // Tracking again: gone once the window holds fewer than kMinLost lost frames.
  for (int i = 0; i < NonPlanarAdvice::kWindow - NonPlanarAdvice::kMinLost + 1; ++i)
    advice.add(outcome(true));
  EXPECT_FALSE(advice.advice());
  EXPECT_TRUE(advice.everShown());
}

// OpenCV's box video (../shared/data/box-video: a box moved by hand over a still table, 640x480):
// its whole first frame as the reference fits no single homography once the box moves, and the
// advice shows; the box's lid cropped from that frame (a plane) is followed and it never shows.
// Measured over the whole clip (track --mode homography): whole frame 117 of 455 registered,
// lid 450 of 455.
TEST(NonPlanarAdvice, ShowsOnTheBoxVideoUnlessTheReferenceIsOneFace) {
  const auto data = test::sharedDataDir();
  if (!data || !std::filesystem::exists(*data / "box-video" / "box.mp4"))
    GTEST_SKIP() << "../shared/data/box-video not present";
  cv::VideoCapture video((*data / "box-video" / "box.mp4").string());
  ASSERT_TRUE(video.isOpened());
  std::vector<cv::Mat> frames;
  for (cv::Mat f; static_cast<int>(frames.size()) < 200 && video.read(f);) frames.push_back(f.clone());
  ASSERT_EQ(frames.size(), 200u);
  const cv::Mat lid = frames[0](cv::Rect(295, 15, 300, 140)).clone();
  for (const bool whole : {true, false}) {
    HomographyTracker tracker(whole ? frames[0] : lid, TrackerParams{});
    NonPlanarAdvice advice;
    int tracked = 0;
    for (const cv::Mat& f : frames) {
      const HomographyTrackResult r = tracker.track(f);
      tracked += r.tracked ? 1 : 0;
      advice.add(r);
    }
    std::printf("%s: %d of %zu registered, advice %s\n", whole ? "whole frame" : "lid", tracked,
                frames.size(), advice.everShown() ? "shown" : "not shown");
    EXPECT_EQ(advice.everShown(), whole);
    if (!whole) {
      EXPECT_GE(tracked, 190);
    }
  }
}
