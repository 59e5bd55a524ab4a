#pragma once
// PlanarTargetTruth: ground truth for real footage of a rectangular planar target (a postcard on
// a table) without a fiducial: its four corners, given by eye in the first frame and refined there
// by cv::cornerSubPix, are carried through the clip by the homography tracker (a plane maps
// exactly by a homography); the rectangle's aspect ratio that fits them best (the top edge's
// length given) and a solvePnP (IPPE) per frame give each frame's world->camera pose, world = the
// target's plane (z = 0, corner 0 at the origin, x along the top edge). The homography of every
// followed frame (frame 0 -> k) is kept too: it carries any point of the plane without the
// guessed K. The corners are carried rather than refined in every frame: on the postcard clip the
// per-frame cornerSubPix corners lie 0.3-1.2 px (worst corner) from both the homography tracker's
// and an independent ECC registration of the card (cv::findTransformECC), which agree with each
// other to 0.04-0.22 px over a grid on the card. The refined corners are kept as a check of that.
// The real-footage tests and `reftrack bench-real` share it.
#include <array>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

struct PlanarTargetTruth {
  std::vector<cv::Point3f> target;  // the rectangle's corners in the world (TL, TR, BR, BL)
  // Per frame, none if lost: the corners carried from frame 0 by the homography (the poses' input)
  // and, as a check, those cornerSubPix finds in the frame itself (equal in frame 0).
  std::vector<std::optional<std::array<cv::Point2f, 4>>> corners, refinedCorners;
  std::vector<std::optional<RigidPose>> poses;           // per frame, from the corners
  std::vector<std::optional<cv::Matx33d>> homographies;  // frame 0 -> frame k, where followed
  double aspectRatio = 0.0;  // left edge / top edge of the best-fitting rectangle (0.8-1.8)
  double aspectRms = 0.0;    // reprojection RMS (px) of that fit over every 20th followed frame

  // frames: the clip (BGR or grey, one size, at least one frame); camera: its intrinsics (the
  // corners are not undistorted: a camera without distortion); cornersInFirstFrame: the target's
  // corners in frames[0] to within a few pixels, top-left, top-right, bottom-right, bottom-left;
  // topEdgeMetres: the length of the edge TL-TR (the scale of the world). Throws
  // reftrack::Error on an empty clip, a frame of another size or a non-positive length.
  static PlanarTargetTruth follow(const std::vector<cv::Mat>& frames, const PinholeCamera& camera,
                                  const std::array<cv::Point2f, 4>& cornersInFirstFrame,
                                  double topEdgeMetres);
};

}  // namespace reftrack
