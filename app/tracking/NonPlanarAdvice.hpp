#pragma once
// NonPlanarAdvice: what homography mode tells a user whose view is not one plane. Homography mode
// follows one flat surface (or a camera turning on the spot); a 3-D object moved over a still
// background (OpenCV's box video, reference = its whole first frame) fits no single homography,
// and the registration check refuses most frames (117 of 455 registered). Cropped to the box's
// lid, the same clip registers 450 of 455. Since the check judges H in its inliers' region (so
// partly planar photos register), the whole frame is instead registered on the moving box alone,
// its inliers spanning a small part of the reference's overlap with the frame. Over a window of
// recent frames, when most were lost and many of those were refused by the registration check, or
// most were registered on a small part of that overlap, advice() says so.
#include <deque>
#include <optional>
#include <string>

#include "engine/homography/HomographyTracker.hpp"

namespace reftrack::app {

class NonPlanarAdvice {
 public:
  static constexpr int kWindow = 30;      // recent frames looked at
  static constexpr int kMinLost = 15;     // lost among them
  static constexpr int kMinRefused = 5;   // of those, refused by the registration check
  static constexpr int kMinPartial = 15;  // registered on a small part of the overlap
  // A registration whose inliers' convex hull covers less than this share of the reference's
  // overlap with the frame is on a small part of it. Measured on the box clip's first 200 frames:
  // the whole frame median 0.17 (the box), the lid crop 0.35 (the lid within its background).
  static constexpr double kMinSupportShare = 0.25;

  // referenceSize, frameSize: of the tracker's reference and this frame (empty: the support of
  // registrations is not judged).
  void add(const HomographyTrackResult& result, cv::Size referenceSize = {},
           cv::Size frameSize = {});
  // The share of the reference's overlap with the frame (the frame's rectangle taken back by H,
  // within the reference's) that the inliers' convex hull covers; nullopt when not tracked.
  static std::optional<double> supportShare(const HomographyTrackResult& result,
                                            cv::Size referenceSize, cv::Size frameSize);
  static const char* message();
  // message() while the recent frames look like a view that is not one plane; nullopt else.
  std::optional<std::string> advice() const;
  bool everShown() const { return everShown_; }  // advice() was set after some add()

 private:
  struct Outcome {
    bool lost = false, refused = false, partial = false;
  };
  std::deque<Outcome> recent_;
  bool everShown_ = false;
};

}  // namespace reftrack::app
