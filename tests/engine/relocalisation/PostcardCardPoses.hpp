#pragma once
// The postcard clip (../shared/data/planar-videos/video-postcard.mp4, 161 frames, 640x480, K
// guessed as fx = fy = 840 at the centre) with a pose per frame from the card's corners (the
// real-footage tests' ground truth, engine/evaluation/PlanarTargetTruth): corners clicked on
// frame 0 and refined there by cornerSubPix, carried by the homography tracker; the card is a
// rectangle of short side 0.105 m whose aspect ratio fits the corners best; solvePnP (IPPE) gives
// each frame's world->camera pose.
#include <array>
#include <opencv2/videoio.hpp>
#include <optional>
#include <vector>

#include "TestPaths.hpp"
#include "engine/evaluation/PlanarTargetTruth.hpp"
#include "engine/geometry/PinholeCamera.hpp"

namespace reftrack::test {

struct PostcardCardPoses {
  std::vector<cv::Mat> frames;
  PinholeCamera camera;
  std::vector<cv::Point3f> card;                                   // the corners, world frame
  std::vector<std::optional<std::array<cv::Point2f, 4>>> corners;  // per frame, none if lost
  std::vector<std::optional<RigidPose>> poses;                     // per frame, from the corners
  std::vector<std::optional<cv::Matx33d>> homographies;  // frame 0 -> frame k, where followed
  double aspectRatio = 0.0;  // of the card's rectangle (long / short side), best fit
  double aspectRms = 0.0;    // reprojection RMS (px) of that fit over a spread of frames

  // nullopt when the clip is not available.
  static std::optional<PostcardCardPoses> load() {
    const auto data = sharedDataDir();
    if (!data) return std::nullopt;
    cv::VideoCapture video((*data / "planar-videos" / "video-postcard.mp4").string());
    if (!video.isOpened()) return std::nullopt;
    PostcardCardPoses p;
    for (cv::Mat f; video.read(f);) p.frames.push_back(f.clone());
    if (p.frames.empty()) return std::nullopt;
    const cv::Size size = p.frames[0].size();
    Eigen::Matrix3d K;
    K << 840, 0, (size.width - 1) * 0.5, 0, 840, (size.height - 1) * 0.5, 0, 0, 1;
    p.camera = PinholeCamera(K, size);
    // Frame-0 corners clicked by eye (top-left, top-right, bottom-right, bottom-left).
    const std::array<cv::Point2f, 4> clicked = {cv::Point2f(64, 115), cv::Point2f(255, 83),
                                                cv::Point2f(312, 285), cv::Point2f(69, 329)};
    PlanarTargetTruth truth = PlanarTargetTruth::follow(p.frames, p.camera, clicked, 0.105);
    p.card = std::move(truth.target);
    p.corners = std::move(truth.corners);
    p.poses = std::move(truth.poses);
    p.homographies = std::move(truth.homographies);
    p.aspectRatio = truth.aspectRatio;
    p.aspectRms = truth.aspectRms;
    return p;
  }
};

}  // namespace reftrack::test
