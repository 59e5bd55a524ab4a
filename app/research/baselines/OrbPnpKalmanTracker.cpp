#include "app/research/baselines/OrbPnpKalmanTracker.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"
#include "engine/geometry/FundamentalMatrix.hpp"
#include "engine/reference/TwoViewTriangulator.hpp"

namespace reftrack::app {

namespace {

// Euler angles (the sample's rot2euler / euler2rot convention: x-y-z, radians).
cv::Vec3d rotationToEuler(const cv::Matx33d& R) {
  const double x = std::atan2(R(2, 1), R(2, 2));
  const double y = std::atan2(-R(2, 0), std::sqrt(R(2, 1) * R(2, 1) + R(2, 2) * R(2, 2)));
  const double z = std::atan2(R(1, 0), R(0, 0));
  return {x, y, z};
}

cv::Matx33d eulerToRotation(const cv::Vec3d& e) {
  const cv::Matx33d Rx(1, 0, 0, 0, std::cos(e[0]), -std::sin(e[0]), 0, std::sin(e[0]),
                       std::cos(e[0]));
  const cv::Matx33d Ry(std::cos(e[1]), 0, std::sin(e[1]), 0, 1, 0, -std::sin(e[1]), 0,
                       std::cos(e[1]));
  const cv::Matx33d Rz(std::cos(e[2]), -std::sin(e[2]), 0, std::sin(e[2]), std::cos(e[2]), 0, 0, 0,
                       1);
  return Rz * Ry * Rx;
}

}  // namespace

OrbPnpKalmanTracker::OrbPnpKalmanTracker(const ReferenceMap& map, OrbPnpKalmanParams params)
    : params_(params), orb_(cv::ORB::create(params.features)) {
  K_ = map.camera.Kcv();
  dist_ = map.camera.distortion();
  // Model, as the sample registers one: ORB keypoints of the reference images with 3D positions.
  // Here the two reference views with their known poses give them: ORB matches A<->B (ratio
  // test), kept when within 1.5 px of the epipolar line, triangulated (Eq. 9 + Eq. 10) and kept
  // when both reprojection errors are below 1 px and the point lies in front of both cameras.
  cv::Ptr<cv::ORB> referenceOrb = cv::ORB::create(2 * params_.features);
  std::vector<cv::KeyPoint> kpA, kpB;
  cv::Mat descA, descB;
  auto grey = [](const cv::Mat& m) {
    cv::Mat g = m;
    if (m.channels() == 3) cv::cvtColor(m, g, cv::COLOR_BGR2GRAY);
    return g;
  };
  referenceOrb->detectAndCompute(grey(map.imageA), cv::noArray(), kpA, descA);
  referenceOrb->detectAndCompute(grey(map.imageB), cv::noArray(), kpB, descB);
  if (descA.empty() || descB.empty())
    throw Error("ORB baseline: no ORB features in the references");
  std::vector<std::vector<cv::DMatch>> knn;
  matcher_.knnMatch(descA, descB, knn, 2);
  std::vector<cv::Point2f> ptsA, ptsB;
  for (const cv::KeyPoint& k : kpA) ptsA.push_back(k.pt);
  for (const cv::KeyPoint& k : kpB) ptsB.push_back(k.pt);
  const std::vector<cv::Point2f> undA = map.camera.undistortPixels(ptsA);
  const std::vector<cv::Point2f> undB = map.camera.undistortPixels(ptsB);
  const RigidPose T_AB = map.T_AB();
  const TwoViewTriangulator triangulator(map.camera.K(), T_AB);
  const Eigen::Matrix3d F = fundamentalMatrix(map.camera.K(), T_AB);
  const RigidPose AtoWorld = map.T_A.inverse();
  for (const auto& m : knn) {
    if (m.size() < 2 || m[0].distance >= params_.ratioTest * m[1].distance) continue;
    const cv::Point2f a = undA[static_cast<std::size_t>(m[0].queryIdx)];
    const cv::Point2f b = undB[static_cast<std::size_t>(m[0].trainIdx)];
    const Eigen::Vector2d pa(a.x, a.y), pb(b.x, b.y);
    const Eigen::Vector3d line = F * Eigen::Vector3d(pa.x(), pa.y(), 1.0);
    if (std::abs(line.dot(Eigen::Vector3d(pb.x(), pb.y(), 1.0))) / line.head<2>().norm() > 1.5)
      continue;
    const Eigen::Vector3d P = triangulator.refine(pa, pb, triangulator.linear(pa, pb));
    if (P.z() <= 0 || (T_AB * P).z() <= 0) continue;
    if (triangulator.reprojectionErrorA(P, pa) > 1.0 ||
        triangulator.reprojectionErrorB(P, pb) > 1.0)
      continue;
    const Eigen::Vector3d Pw = AtoWorld * P;
    for (int view = 0; view < 2; ++view) {
      modelPoints_.emplace_back(static_cast<float>(Pw.x()), static_cast<float>(Pw.y()),
                                static_cast<float>(Pw.z()));
      modelDescriptors_.push_back(view == 0 ? descA.row(m[0].queryIdx) : descB.row(m[0].trainIdx));
    }
  }
  if (modelPoints_.size() < 6)
    throw Error("ORB baseline: fewer than 6 map points have descriptors");

  // The sample's Kalman filter: 18 states, 6 measurements, constant acceleration.
  kf_.init(18, 6, 0, CV_64F);
  cv::setIdentity(kf_.processNoiseCov, cv::Scalar::all(1e-5));
  cv::setIdentity(kf_.measurementNoiseCov, cv::Scalar::all(1e-4));
  cv::setIdentity(kf_.errorCovPost, cv::Scalar::all(1));
  const double dt = params_.dt;
  kf_.transitionMatrix = cv::Mat::eye(18, 18, CV_64F);
  for (int block : {0, 9}) {
    for (int i = 0; i < 3; ++i) {
      kf_.transitionMatrix.at<double>(block + i, block + 3 + i) = dt;
      kf_.transitionMatrix.at<double>(block + 3 + i, block + 6 + i) = dt;
      kf_.transitionMatrix.at<double>(block + i, block + 6 + i) = 0.5 * dt * dt;
    }
  }
  kf_.measurementMatrix = cv::Mat::zeros(6, 18, CV_64F);
  for (int i = 0; i < 3; ++i) {
    kf_.measurementMatrix.at<double>(i, i) = 1;
    kf_.measurementMatrix.at<double>(3 + i, 9 + i) = 1;
  }
}

void OrbPnpKalmanTracker::reset() {
  initialised_ = false;
  cv::setIdentity(kf_.errorCovPost, cv::Scalar::all(1));
}

std::optional<RigidPose> OrbPnpKalmanTracker::process(const cv::Mat& frame) {
  cv::Mat gray = frame;
  if (frame.channels() == 3) cv::cvtColor(frame, gray, cv::COLOR_BGR2GRAY);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb_->detectAndCompute(gray, cv::noArray(), keypoints, descriptors);
  lastInliers_ = 0;
  std::optional<cv::Mat> measurement;
  if (!descriptors.empty()) {
    std::vector<std::vector<cv::DMatch>> knn;
    matcher_.knnMatch(descriptors, modelDescriptors_, knn, 2);
    std::vector<cv::Point3f> object;
    std::vector<cv::Point2f> image;
    for (const auto& m : knn)
      if (m.size() == 2 && m[0].distance < params_.ratioTest * m[1].distance) {
        object.push_back(modelPoints_[static_cast<std::size_t>(m[0].trainIdx)]);
        image.push_back(keypoints[static_cast<std::size_t>(m[0].queryIdx)].pt);
      }
    if (object.size() >= 6) {
      cv::Mat rvec, tvec;
      std::vector<int> inliers;
      if (cv::solvePnPRansac(object, image, K_, dist_, rvec, tvec, false, params_.ransacIterations,
                             params_.reprojectionErrorPx, params_.confidence, inliers,
                             cv::SOLVEPNP_EPNP)) {
        lastInliers_ = static_cast<int>(inliers.size());
        if (lastInliers_ >= params_.minInliersKalman) {
          cv::Matx33d R;
          cv::Rodrigues(rvec, R);
          const cv::Vec3d e = rotationToEuler(R);
          cv::Mat z = (cv::Mat_<double>(6, 1) << tvec.at<double>(0), tvec.at<double>(1),
                       tvec.at<double>(2), e[0], e[1], e[2]);
          measurement = z;
        }
      }
    }
  }
  if (!initialised_) {
    if (!measurement) return std::nullopt;
    kf_.statePost = cv::Mat::zeros(18, 1, CV_64F);
    for (int i = 0; i < 3; ++i) {
      kf_.statePost.at<double>(i) = measurement->at<double>(i);
      kf_.statePost.at<double>(9 + i) = measurement->at<double>(3 + i);
    }
    initialised_ = true;
  } else {
    kf_.predict();
    if (measurement) {
      kf_.correct(*measurement);
    } else {
      kf_.statePre.copyTo(kf_.statePost);
    }
  }
  const cv::Mat& s = kf_.statePost;
  const cv::Matx33d R = eulerToRotation({s.at<double>(9), s.at<double>(10), s.at<double>(11)});
  Eigen::Matrix3d Re;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Re(r, c) = R(r, c);
  return RigidPose(Re, Eigen::Vector3d(s.at<double>(0), s.at<double>(1), s.at<double>(2)));
}

}  // namespace reftrack::app
