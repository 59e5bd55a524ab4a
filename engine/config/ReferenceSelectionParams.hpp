#pragma once
// ReferenceSelectionParams (YAML section `references`): which two references of a
// MultiReferenceMap the 6-DOF tracker runs on (ReferenceSelector) and how the
// MultiReferenceTracker hands over between pairs and recovers (issue 13).
#include <opencv2/core.hpp>

#include "engine/config/ParamSection.hpp"

namespace reftrack {

struct ReferenceSelectionParams : ParamSection<ReferenceSelectionParams> {
  static constexpr const char* kSection = "references";

  // A reference's cost for a camera pose: distance between the camera centres divided by the
  // scene depth (the references' median distance to their map points) plus angleWeight times the
  // angle between the viewing directions (radians). A pair costs the sum of its two references.
  double angleWeight = 1.0;
  int minSharedPoints = 30;   // pairs sharing fewer map points are never used
  double switchMargin = 0.2;  // another pair must cost this fraction less than the pair in use ...
  int switchAfterFrames = 3;  // ... on this many consecutive frames before the tracker switches
  int cachedTrackers = 4;     // pair trackers kept ready (each holds its two prepared images)
  // Lost for at most this many frames: first try the last pose as a seed for the pair in use (the
  // camera has not gone far: a black or blurred frame), before relocalising.
  int reseedFrames = 30;

  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
};
extern template struct ParamSection<ReferenceSelectionParams>;  // defined in
                                                                // ReferenceSelectionParams.cpp

}  // namespace reftrack
