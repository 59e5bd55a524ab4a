#pragma once
// The postcard clip (../shared/data/planar-videos/video-postcard.mp4, 161 frames, 640x480, K
// guessed as fx = fy = 840 at the centre) with a pose per frame from the card's corners (the
// real-footage tests' ground truth): corners clicked on frame 0, followed by
// the homography tracker, refined by cornerSubPix; the card is a rectangle of short side 0.105 m
// whose aspect ratio fits the corners best; solvePnP (IPPE) gives each frame's world->camera pose.
#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <optional>
#include <vector>

#include "TestPaths.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/homography/HomographyTracker.hpp"

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
    p.measure();
    return p;
  }

 private:
  static std::array<cv::Point2f, 4> refined(const cv::Mat& bgr, std::array<cv::Point2f, 4> c) {
    cv::Mat gray;
    cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
    std::vector<cv::Point2f> v(c.begin(), c.end());
    cv::cornerSubPix(gray, v, cv::Size(5, 5), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 40, 0.01));
    std::copy(v.begin(), v.end(), c.begin());
    return c;
  }
  static std::vector<cv::Point3f> rectangle(double w, double h) {
    return {{0, 0, 0},
            {static_cast<float>(w), 0, 0},
            {static_cast<float>(w), static_cast<float>(h), 0},
            {0, static_cast<float>(h), 0}};
  }
  static double pnp(const std::vector<cv::Point3f>& object, const std::array<cv::Point2f, 4>& c,
                    const cv::Mat& K, cv::Mat& rvec, cv::Mat& tvec) {
    std::vector<cv::Point2f> pts(c.begin(), c.end()), back;
    cv::solvePnP(object, pts, K, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_IPPE);
    cv::projectPoints(object, rvec, tvec, K, cv::noArray(), back);
    double sum = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) sum += std::pow(cv::norm(pts[i] - back[i]), 2);
    return std::sqrt(sum / static_cast<double>(pts.size()));
  }

  void measure() {
    const cv::Size size = frames[0].size();
    Eigen::Matrix3d K;
    K << 840, 0, (size.width - 1) * 0.5, 0, 840, (size.height - 1) * 0.5, 0, 0, 1;
    camera = PinholeCamera(K, size);
    const cv::Mat Kcv(camera.Kcv());
    // Frame-0 corners clicked by eye (top-left, top-right, bottom-right, bottom-left).
    const std::array<cv::Point2f, 4> clicked = {cv::Point2f(64, 115), cv::Point2f(255, 83),
                                                cv::Point2f(312, 285), cv::Point2f(69, 329)};
    const std::array<cv::Point2f, 4> corners0 = refined(frames[0], clicked);
    HomographyTracker homography(frames[0], TrackerParams{});
    corners.assign(frames.size(), std::nullopt);
    homographies.assign(frames.size(), std::nullopt);
    for (std::size_t k = 0; k < frames.size(); ++k) {
      const HomographyTrackResult h = homography.track(frames[k]);
      if (!h.tracked) continue;
      homographies[k] = h.H;
      std::vector<cv::Point2f> in(corners0.begin(), corners0.end()), out;
      cv::perspectiveTransform(in, out, cv::Mat(h.H));
      std::array<cv::Point2f, 4> c;
      std::copy(out.begin(), out.end(), c.begin());
      corners[k] = refined(frames[k], c);
    }
    double bestRatio = 1.0, bestRms = 1e9;
    for (double ratio = 0.8; ratio <= 1.8; ratio += 0.005) {
      double rms = 0;
      int n = 0;
      for (std::size_t k = 0; k < corners.size(); k += 20) {
        if (!corners[k]) continue;
        cv::Mat rvec, tvec;
        rms += pnp(rectangle(0.105, 0.105 * ratio), *corners[k], Kcv, rvec, tvec);
        ++n;
      }
      rms /= std::max(n, 1);
      if (rms < bestRms) {
        bestRms = rms;
        bestRatio = ratio;
      }
    }
    card = rectangle(0.105, 0.105 * bestRatio);
    aspectRatio = bestRatio;
    aspectRms = bestRms;
    poses.assign(frames.size(), std::nullopt);
    for (std::size_t k = 0; k < frames.size(); ++k) {
      if (!corners[k]) continue;
      cv::Mat rvec, tvec;
      pnp(card, *corners[k], Kcv, rvec, tvec);
      Vector6d x;
      x << tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2), rvec.at<double>(0),
          rvec.at<double>(1), rvec.at<double>(2);
      poses[k] = RigidPose::fromVector6(x);
    }
  }
};

}  // namespace reftrack::test
