#pragma once
// MapExtensionParams (YAML section `extension`): when `reftrack extend` adds a reference to the
// map from a tracked video frame, and how the new reference is matched to the existing ones.
// Support figures of the tracker are pixels at 320x240 (scaled with the image, as the tracker's).
#include <opencv2/core.hpp>

#include "engine/config/ParamSection.hpp"

namespace reftrack {

struct MapExtensionParams : ParamSection<MapExtensionParams> {
  static constexpr const char* kSection = "extension";

  // A tracked frame is covered when some reference's camera centre lies within
  // maxDistanceMetres of the frame's and its optical axis within maxAngleDeg of the frame's;
  // an uncovered frame becomes a new reference (when well supported, below). The simulator's
  // reference pair is 0.25 m apart at about 1 m from the content (about 14 degrees).
  double maxDistanceMetres = 0.2;
  double maxAngleDeg = 15.0;
  // Well supported: at least this many inliers and a support SD (PoseSupport) at most this.
  int minInliers = 40;
  double maxSupportSdPx = 0.15;
  // The new reference is matched (epipolar-guided, as in preparation) to at most this many
  // existing references, those with the most map points in its view first, each with at least
  // minOverlapPoints of them.
  int matchReferences = 3;
  int minOverlapPoints = 30;
  // The tracked pose is a few millimetres off until the bundle adjustment, so the epipolar and
  // reprojection gates of this matching are wider than preparation's (pixels of the image).
  double maxEpipolarDistancePx = 3.0;
  double maxReprojectionErrorPx = 3.0;
  // A frame whose matching yields fewer map points than this is not added (it could not be
  // tracked against, nor adjusted).
  int minNewPoints = 30;
  int maxReferences = 64;  // no more references are added beyond this many

  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
};
extern template struct ParamSection<MapExtensionParams>;  // defined in MapExtensionParams.cpp

}  // namespace reftrack
