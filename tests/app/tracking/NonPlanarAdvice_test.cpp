#include "app/tracking/NonPlanarAdvice.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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

// The support share: inliers spanning a quarter of a reference seen whole (H = identity) cover
// 0.25 of the overlap; the frame shifted by half its width halves the overlap, so 0.5; fewer than
// three inliers span nothing; a lost frame has no share.
TEST(NonPlanarAdvice, SupportShareIsTheInliersHullOverTheOverlap) {
  HomographyTrackResult r = outcome(true);
  for (const cv::Point2f p : {cv::Point2f(0, 0), cv::Point2f(100, 0), cv::Point2f(100, 100),
                              cv::Point2f(0, 100), cv::Point2f(50, 50)})
    r.inlierMatches.emplace_back(p, p);
  const cv::Size size(200, 200);
  EXPECT_NEAR(*NonPlanarAdvice::supportShare(r, size, size), 0.25, 1e-6);
  r.H = cv::Matx33d(1, 0, 100, 0, 1, 0, 0, 0, 1);  // reference x -> frame x + 100
  EXPECT_NEAR(*NonPlanarAdvice::supportShare(r, size, size), 0.5, 1e-6);
  r.inlierMatches.resize(2);
  EXPECT_EQ(*NonPlanarAdvice::supportShare(r, size, size), 0.0);
  EXPECT_FALSE(NonPlanarAdvice::supportShare(outcome(false), size, size));
  EXPECT_FALSE(NonPlanarAdvice::supportShare(r, {}, size));
}

// Registrations on a small part of the overlap, most of the window: the advice shows.
TEST(NonPlanarAdvice, ShowsWhenMostRegistrationsFollowASmallPart) {
  HomographyTrackResult r = outcome(true);
  for (const cv::Point2f p : {cv::Point2f(0, 0), cv::Point2f(40, 0), cv::Point2f(40, 40)})
    r.inlierMatches.emplace_back(p, p);
  NonPlanarAdvice advice;
  for (int i = 0; i < NonPlanarAdvice::kMinPartial - 1; ++i) advice.add(r, {200, 200}, {200, 200});
  EXPECT_FALSE(advice.advice());
  advice.add(r, {200, 200}, {200, 200});
  EXPECT_TRUE(advice.advice());
}

// OpenCV's box video (../shared/data/box-video: a box moved by hand over a still table, 640x480):
// its whole first frame as the reference fits no single homography once the box moves: it is
// registered on the box alone (188 of the first 200 frames, the inliers' hull a median 0.17 of
// the overlap) and the advice shows; the box's lid cropped from that frame (a plane) is followed
// (200 of 200, median share 0.35) and it never shows.
TEST(NonPlanarAdvice, ShowsOnTheBoxVideoUnlessTheReferenceIsOneFace) {
  const auto data = test::sharedDataDir();
  if (!data || !std::filesystem::exists(*data / "box-video" / "box.mp4"))
    GTEST_SKIP() << "../shared/data/box-video not present";
  cv::VideoCapture video((*data / "box-video" / "box.mp4").string());
  ASSERT_TRUE(video.isOpened());
  std::vector<cv::Mat> frames;
  for (cv::Mat f; static_cast<int>(frames.size()) < 200 && video.read(f);)
    frames.push_back(f.clone());
  ASSERT_EQ(frames.size(), 200u);
  const cv::Mat lid = frames[0](cv::Rect(295, 15, 300, 140)).clone();
  for (const bool whole : {true, false}) {
    HomographyTracker tracker(whole ? frames[0] : lid, TrackerParams{});
    NonPlanarAdvice advice;
    int tracked = 0;
    std::vector<double> shares;
    for (const cv::Mat& f : frames) {
      const HomographyTrackResult r = tracker.track(f);
      tracked += r.tracked ? 1 : 0;
      advice.add(r, tracker.referenceSize(), f.size());
      if (const auto share = NonPlanarAdvice::supportShare(r, tracker.referenceSize(), f.size()))
        shares.push_back(*share);
    }
    ASSERT_FALSE(shares.empty());
    std::nth_element(shares.begin(), shares.begin() + shares.size() / 2, shares.end());
    std::printf("%s: %d of %zu registered, median support share %.2f, advice %s\n",
                whole ? "whole frame" : "lid", tracked, frames.size(), shares[shares.size() / 2],
                advice.everShown() ? "shown" : "not shown");
    EXPECT_EQ(advice.everShown(), whole);
    if (!whole) {
      EXPECT_GE(tracked, 190);
    }
  }
}
