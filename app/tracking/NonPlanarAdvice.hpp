#pragma once
// NonPlanarAdvice: what homography mode tells a user whose view is not one plane. Homography mode
// follows one flat surface (or a camera turning on the spot); a 3-D object moved over a still
// background (OpenCV's box video, reference = its whole first frame) fits no single homography,
// and the registration check refuses most frames (117 of 455 registered). Cropped to the box's
// lid, the same clip registers 450 of 455. Over a window of recent frames, when most were lost and
// many of those were refused by the registration check, advice() says so.
#include <deque>
#include <optional>
#include <string>

#include "engine/homography/HomographyTracker.hpp"

namespace reftrack::app {

class NonPlanarAdvice {
 public:
  static constexpr int kWindow = 30;     // recent frames looked at
  static constexpr int kMinLost = 15;    // lost among them
  static constexpr int kMinRefused = 5;  // of those, refused by the registration check

  void add(const HomographyTrackResult& result);
  static const char* message();
  // message() while the recent frames look like a view that is not one plane; nullopt else.
  std::optional<std::string> advice() const;
  bool everShown() const { return everShown_; }  // advice() was set after some add()

 private:
  struct Outcome {
    bool lost = false, refused = false;
  };
  std::deque<Outcome> recent_;
  bool everShown_ = false;
};

}  // namespace reftrack::app
