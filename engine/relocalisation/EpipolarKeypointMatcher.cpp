#include "engine/relocalisation/EpipolarKeypointMatcher.hpp"

#include <cmath>
#include <limits>

#include "engine/core/Error.hpp"
#include "engine/relocalisation/KeypointFeatures.hpp"

namespace reftrack {

namespace {

struct Nearest {
  int index = -1;
  float best = std::numeric_limits<float>::max();
  float second = std::numeric_limits<float>::max();
  void offer(int other, float distance) {
    if (distance < best) {
      second = best;
      best = distance;
      index = other;
    } else if (distance < second) {
      second = distance;
    }
  }
};

}  // namespace

std::vector<std::pair<int, int>> matchAlongEpipolarLines(
    const Eigen::Matrix3d& F, const std::vector<cv::Point2f>& idealI,
    const std::vector<double>& toleranceI, const cv::Mat& descriptorsI,
    const std::vector<cv::Point2f>& idealJ, const std::vector<double>& toleranceJ,
    const cv::Mat& descriptorsJ, int normType, const EpipolarKeypointMatcherParams& params) {
  const std::size_t nI = idealI.size(), nJ = idealJ.size();
  if (toleranceI.size() != nI || toleranceJ.size() != nJ ||
      descriptorsI.rows != static_cast<int>(nI) || descriptorsJ.rows != static_cast<int>(nJ))
    throw Error("epipolar keypoint matching: one pixel, tolerance and descriptor per keypoint");
  std::vector<std::pair<int, int>> out;
  if (nI == 0 || nJ == 0) return out;
  if (descriptorsI.type() != descriptorsJ.type() || descriptorsI.cols != descriptorsJ.cols)
    throw Error("epipolar keypoint matching: the two views' descriptors differ in kind");
  const float maxDistance =
      static_cast<float>(params.maxDistanceFraction *
                         (normType == cv::NORM_HAMMING ? 8.0 * descriptorsI.cols : 2.0 * 512.0));
  // Lines of i's keypoints in j, and of j's keypoints in i, normalised (a, b unit).
  const auto lines = [](const Eigen::Matrix3d& M, const std::vector<cv::Point2f>& points) {
    std::vector<Eigen::Vector3d> out;
    out.reserve(points.size());
    for (const cv::Point2f& p : points) {
      Eigen::Vector3d l = M * Eigen::Vector3d(p.x, p.y, 1.0);
      const double n = std::hypot(l.x(), l.y());
      out.push_back(n > 1e-12
                        ? Eigen::Vector3d(l / n)
                        : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
    }
    return out;
  };
  const std::vector<Eigen::Vector3d> linesInJ = lines(F, idealI);
  const std::vector<Eigen::Vector3d> linesInI = lines(F.transpose(), idealJ);
  std::vector<Nearest> ofI(nI), ofJ(nJ);
  for (std::size_t a = 0; a < nI; ++a) {
    const Eigen::Vector3d& l = linesInJ[a];
    if (!l.allFinite()) continue;
    for (std::size_t b = 0; b < nJ; ++b) {
      const cv::Point2f& q = idealJ[b];
      if (std::abs(l.x() * q.x + l.y() * q.y + l.z()) > toleranceJ[b]) continue;
      const Eigen::Vector3d& m = linesInI[b];
      const cv::Point2f& p = idealI[a];
      if (!m.allFinite() || std::abs(m.x() * p.x + m.y() * p.y + m.z()) > toleranceI[a]) continue;
      const float d = descriptorDistance(descriptorsI, static_cast<int>(a), descriptorsJ,
                                         static_cast<int>(b), normType);
      ofI[a].offer(static_cast<int>(b), d);
      ofJ[b].offer(static_cast<int>(a), d);
    }
  }
  const float ratio = static_cast<float>(params.ratio);
  for (std::size_t a = 0; a < nI; ++a) {
    const Nearest& n = ofI[a];
    if (n.index < 0 || n.best > maxDistance || !(n.best < ratio * n.second)) continue;
    const Nearest& back = ofJ[static_cast<std::size_t>(n.index)];
    if (back.index != static_cast<int>(a) || !(back.best < ratio * back.second)) continue;
    out.emplace_back(static_cast<int>(a), n.index);
  }
  return out;
}

}  // namespace reftrack
