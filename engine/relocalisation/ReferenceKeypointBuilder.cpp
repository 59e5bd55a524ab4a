#include "engine/relocalisation/ReferenceKeypointBuilder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/relocalisation/EpipolarKeypointMatcher.hpp"
#include "engine/relocalisation/KeypointFeatures.hpp"

namespace reftrack {

namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

double lineDistance(const Eigen::Vector3d& line, cv::Point2d x) {
  const double n = std::hypot(line.x(), line.y());
  return n > 0 ? std::abs(line.x() * x.x + line.y() * x.y + line.z()) / n
               : std::numeric_limits<double>::infinity();
}

double reprojectionError(const Eigen::Matrix3d& K, const RigidPose& T, const Eigen::Vector3d& X,
                         cv::Point2d x, double* depth) {
  const Eigen::Vector3d c = T * X;
  *depth = c.z();
  if (c.z() <= 0) return std::numeric_limits<double>::infinity();
  const Eigen::Vector3d p = K * (c / c.z());
  return std::hypot(p.x() - x.x, p.y() - x.y);
}

}  // namespace

std::optional<Eigen::Vector3d> triangulateKeypointMatch(const Eigen::Matrix3d& K,
                                                        const RigidPose& Ti, cv::Point2d xi,
                                                        double toleranceI, const RigidPose& Tj,
                                                        cv::Point2d xj, double toleranceJ,
                                                        double minParallaxDeg) {
  // Epipolar check first (cheap): F maps a pixel of i to its line in j.
  const RigidPose Tij = Tj * Ti.inverse();
  const Eigen::Matrix3d Kinv = K.inverse();
  const Eigen::Matrix3d F = Kinv.transpose() * skew(Tij.translation()) * Tij.rotation() * Kinv;
  const Eigen::Vector3d hi(xi.x, xi.y, 1.0), hj(xj.x, xj.y, 1.0);
  if (lineDistance(F * hi, xj) > toleranceJ || lineDistance(F.transpose() * hj, xi) > toleranceI)
    return std::nullopt;
  // DLT through OpenCV (the same SVD as a hand-written one).
  const Eigen::Matrix<double, 3, 4> Pi = K * Ti.matrix3x4(), Pj = K * Tj.matrix3x4();
  cv::Mat cvPi(3, 4, CV_64F), cvPj(3, 4, CV_64F);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      cvPi.at<double>(r, c) = Pi(r, c);
      cvPj.at<double>(r, c) = Pj(r, c);
    }
  cv::Mat X4;
  cv::triangulatePoints(cvPi, cvPj, cv::Mat(cv::Matx21d(xi.x, xi.y)),
                        cv::Mat(cv::Matx21d(xj.x, xj.y)), X4);
  const double w = X4.at<double>(3);
  if (std::abs(w) < 1e-12) return std::nullopt;  // at infinity
  const Eigen::Vector3d X(X4.at<double>(0) / w, X4.at<double>(1) / w, X4.at<double>(2) / w);
  double depthI = 0, depthJ = 0;
  if (reprojectionError(K, Ti, X, xi, &depthI) > toleranceI ||
      reprojectionError(K, Tj, X, xj, &depthJ) > toleranceJ)
    return std::nullopt;  // also behind either camera (infinite error)
  const Eigen::Vector3d rayI = (X - Ti.cameraCentre()).normalized();
  const Eigen::Vector3d rayJ = (X - Tj.cameraCentre()).normalized();
  const double parallaxDeg = std::acos(std::clamp(rayI.dot(rayJ), -1.0, 1.0)) * 180.0 / M_PI;
  if (parallaxDeg < minParallaxDeg) return std::nullopt;
  return X;
}

void buildReferenceKeypoints(MultiReferenceMap& map, const RelocalisationParams& params) {
  params.check();
  if (map.views.size() < 2) throw Error("buildReferenceKeypoints: the map needs two views or more");
  const cv::Size size = map.camera.imageSize();
  for (const ReferenceView& v : map.views)
    if (v.image.empty() || v.image.size() != size)
      throw Error("buildReferenceKeypoints: reference '" + v.name + "' is not " +
                  std::to_string(size.width) + "x" + std::to_string(size.height));
  const KeypointFeatures features(params.keypoints);
  // The ORB pyramid of a reference gets params.referenceFinerLevels levels above the image
  // (upsampled 1.2x each): a view at half the reference's distance sees finer keypoints than the
  // reference's finest. ORB shares the keypoints out 1.2x more per finer level, so the cap grows
  // by a quarter per finer level (7/4 for 3: about as many keypoints stay at the image's own
  // levels; the exact geometric share would be 1.95, more descriptors to match per attempt).
  // Two more coarser levels (4500 keypoints) changed nothing on the same views.
  const bool orb = params.keypoints == "orb";
  const int finerLevels = orb ? params.referenceFinerLevels : 0;
  const int count = params.featuresPerReferenceFor(size) * (4 + finerLevels) / 4;
  const double tolerance = params.triangulationPx * resolutionScale(size);
  const std::size_t n = map.views.size();

  // 1. Keypoints of every view, their ideal pixels and the pixel tolerance of each: a keypoint
  // found at a coarser scale is localised proportionally less precisely (capped at 4x).
  std::vector<std::vector<cv::Point2f>> ideal(n);
  std::vector<std::vector<double>> tol(n);
  std::vector<std::vector<double>> parallax(n);  // of each keypoint's point so far, -1 = none
  for (std::size_t v = 0; v < n; ++v) {
    ReferenceKeypoints& layer = map.views[v].keypoints;
    layer = ReferenceKeypoints{};
    features.detectAndDescribe(map.views[v].image, count, layer.keypoints, layer.descriptors,
                               finerLevels);
    const Eigen::Vector3d none =
        Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    layer.points.assign(layer.keypoints.size(), none);
    std::vector<cv::Point2f> px;
    float smallest = std::numeric_limits<float>::max();
    for (const cv::KeyPoint& k : layer.keypoints) {
      px.push_back(k.pt);
      smallest = std::min(smallest, std::max(k.size, 1e-3f));
    }
    // The finest keypoints of the image itself set the unit tolerance (the upsampled levels'
    // are no better located than those).
    smallest *= std::pow(1.2f, static_cast<float>(finerLevels));
    ideal[v] = map.camera.undistortPixels(px);
    for (const cv::KeyPoint& k : layer.keypoints)
      tol[v].push_back(tolerance * std::clamp(static_cast<double>(k.size / smallest), 1.0, 4.0));
    parallax[v].assign(layer.keypoints.size(), -1.0);
  }

  // 2. Every pair: mutual ratio-test matches, triangulated under the known poses.
  const Eigen::Matrix3d& K = map.camera.K();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      ReferenceKeypoints& li = map.views[i].keypoints;
      ReferenceKeypoints& lj = map.views[j].keypoints;
      if (li.empty() || lj.empty()) continue;
      const RigidPose& Ti = map.views[i].T;
      const RigidPose& Tj = map.views[j].T;
      // Epipolar-guided (EpipolarKeypointMatcher): the known poses narrow each keypoint's
      // candidates to those near its line, so repeated texture keeps its matches.
      const RigidPose Tij = Tj * Ti.inverse();
      const Eigen::Matrix3d Kinv = K.inverse();
      const Eigen::Matrix3d F = Kinv.transpose() * skew(Tij.translation()) * Tij.rotation() * Kinv;
      EpipolarKeypointMatcherParams matching;
      matching.ratio = params.ratio;
      for (const auto& [ia, jb] :
           matchAlongEpipolarLines(F, ideal[i], tol[i], li.descriptors, ideal[j], tol[j],
                                   lj.descriptors, features.normType(), matching)) {
        const auto a = static_cast<std::size_t>(ia), b = static_cast<std::size_t>(jb);
        const std::optional<Eigen::Vector3d> X = triangulateKeypointMatch(
            K, Ti, ideal[i][a], tol[i][a], Tj, ideal[j][b], tol[j][b], params.minParallaxDeg);
        if (!X) continue;
        const double angle = std::acos(std::clamp(
            (*X - Ti.cameraCentre()).normalized().dot((*X - Tj.cameraCentre()).normalized()), -1.0,
            1.0));
        if (angle > parallax[i][a]) {
          parallax[i][a] = angle;
          li.points[a] = *X;
        }
        if (angle > parallax[j][b]) {
          parallax[j][b] = angle;
          lj.points[b] = *X;
        }
      }
    }
  map.keypointKind = params.keypoints;
}

}  // namespace reftrack
