#include "engine/evaluation/PlanarTargetTruth.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "engine/config/TrackerParams.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/homography/HomographyTracker.hpp"

namespace reftrack {

namespace {

std::array<cv::Point2f, 4> refined(const cv::Mat& image, std::array<cv::Point2f, 4> c) {
  const cv::Mat gray = toGray8(image);
  std::vector<cv::Point2f> v(c.begin(), c.end());
  cv::cornerSubPix(gray, v, cv::Size(5, 5), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 40, 0.01));
  std::copy(v.begin(), v.end(), c.begin());
  return c;
}

std::vector<cv::Point3f> rectangle(double w, double h) {
  return {{0, 0, 0},
          {static_cast<float>(w), 0, 0},
          {static_cast<float>(w), static_cast<float>(h), 0},
          {0, static_cast<float>(h), 0}};
}

// IPPE pose of the rectangle from its four corners; returns the reprojection RMS (px).
double pnp(const std::vector<cv::Point3f>& object, const std::array<cv::Point2f, 4>& c,
           const cv::Mat& K, cv::Mat& rvec, cv::Mat& tvec) {
  std::vector<cv::Point2f> pts(c.begin(), c.end()), back;
  cv::solvePnP(object, pts, K, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_IPPE);
  cv::projectPoints(object, rvec, tvec, K, cv::noArray(), back);
  double sum = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) sum += std::pow(cv::norm(pts[i] - back[i]), 2);
  return std::sqrt(sum / static_cast<double>(pts.size()));
}

}  // namespace

PlanarTargetTruth PlanarTargetTruth::follow(const std::vector<cv::Mat>& frames,
                                            const PinholeCamera& camera,
                                            const std::array<cv::Point2f, 4>& cornersInFirstFrame,
                                            double topEdgeMetres) {
  if (frames.empty()) throw Error("planar target truth: the clip has no frames");
  if (!(topEdgeMetres > 0) || !std::isfinite(topEdgeMetres))
    throw Error("planar target truth: the target's top edge must be > 0 m");
  const cv::Size size = frames[0].size();
  for (std::size_t k = 0; k < frames.size(); ++k)
    if (frames[k].size() != size)
      throw Error("planar target truth: frame " + std::to_string(k) + " is " +
                  std::to_string(frames[k].cols) + "x" + std::to_string(frames[k].rows) +
                  ", frame 0 " + std::to_string(size.width) + "x" + std::to_string(size.height));
  const cv::Mat Kcv(camera.Kcv());
  PlanarTargetTruth t;
  const std::array<cv::Point2f, 4> corners0 = refined(frames[0], cornersInFirstFrame);
  HomographyTracker homography(frames[0], TrackerParams{});
  t.corners.assign(frames.size(), std::nullopt);
  t.refinedCorners.assign(frames.size(), std::nullopt);
  t.homographies.assign(frames.size(), std::nullopt);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const HomographyTrackResult h = homography.track(frames[k]);
    if (!h.tracked) continue;
    t.homographies[k] = h.H;
    std::vector<cv::Point2f> in(corners0.begin(), corners0.end()), out;
    cv::perspectiveTransform(in, out, cv::Mat(h.H));
    std::array<cv::Point2f, 4> c;
    std::copy(out.begin(), out.end(), c.begin());
    t.corners[k] = k == 0 ? corners0 : c;
    t.refinedCorners[k] = k == 0 ? corners0 : refined(frames[k], c);
  }
  // The aspect ratio: a 0.005 grid search of the mean IPPE reprojection RMS over a spread of
  // frames (every 20th).
  double bestRatio = 1.0, bestRms = 1e9;
  for (double ratio = 0.8; ratio <= 1.8; ratio += 0.005) {
    double rms = 0;
    int n = 0;
    for (std::size_t k = 0; k < t.corners.size(); k += 20) {
      if (!t.corners[k]) continue;
      cv::Mat rvec, tvec;
      rms += pnp(rectangle(topEdgeMetres, topEdgeMetres * ratio), *t.corners[k], Kcv, rvec, tvec);
      ++n;
    }
    rms /= std::max(n, 1);
    if (rms < bestRms) {
      bestRms = rms;
      bestRatio = ratio;
    }
  }
  t.target = rectangle(topEdgeMetres, topEdgeMetres * bestRatio);
  t.aspectRatio = bestRatio;
  t.aspectRms = bestRms;
  t.poses.assign(frames.size(), std::nullopt);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (!t.corners[k]) continue;
    cv::Mat rvec, tvec;
    pnp(t.target, *t.corners[k], Kcv, rvec, tvec);
    Vector6d x;
    x << tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2), rvec.at<double>(0),
        rvec.at<double>(1), rvec.at<double>(2);
    t.poses[k] = RigidPose::fromVector6(x);
  }
  return t;
}

}  // namespace reftrack
