#include "engine/reference/TwoViewMotion.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "engine/core/Error.hpp"
#include "engine/relocalisation/KeypointFeatures.hpp"

namespace reftrack {

namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

std::string fixed(double v, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// The unit viewing ray of an undistorted pixel.
Eigen::Vector3d rayOf(const Eigen::Matrix3d& Kinv, const cv::Point2f& p) {
  return (Kinv * Eigen::Vector3d(p.x, p.y, 1.0)).normalized();
}

// The rotation R minimising sum |b[i] - R a[i]|^2 over unit rays (Kabsch; Eigen's SVD).
Eigen::Matrix3d rotationBetween(const std::vector<Eigen::Vector3d>& a,
                                const std::vector<Eigen::Vector3d>& b) {
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) M += b[i] * a[i].transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

// Pixel distance between where `R` takes ray `a` and the pixel `b`.
double rotatedDistancePx(const Eigen::Matrix3d& K, const Eigen::Matrix3d& R,
                         const Eigen::Vector3d& a, const cv::Point2f& b) {
  const Eigen::Vector3d q = K * (R * a);
  if (!(q.z() > 1e-12)) return INFINITY;
  return (q.head<2>() / q.z() - Eigen::Vector2d(b.x, b.y)).norm();
}

// "right" / "left", "down" / "up", "forward" / "back": the largest components of a unit
// direction in the first camera's frame.
std::string directionWords(const Eigen::Vector3d& d) {
  static const char* positive[] = {"right", "down", "forward"};
  static const char* negative[] = {"left", "up", "back"};
  std::string out;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 0.3) continue;
    if (!out.empty()) out += " and ";
    out += d[a] > 0 ? positive[a] : negative[a];
  }
  return out.empty() ? "nowhere" : out;
}

}  // namespace

std::string TwoViewMotion::summary() const {
  std::string s = std::to_string(matches) + " keypoint matches, " + std::to_string(inliers) +
                  " fit the essential matrix";
  if (inliers > 0) {
    s += "; parallax " + fixed(medianParallaxDeg, 2) + " deg (" + fixed(medianParallaxPx, 1) +
         " px, median); a rotation alone explains " + fixed(100.0 * rotationShare, 0) + "% of them";
    if (homographyInliers > 0)
      s += ", a plane's homography " + std::to_string(homographyInliers) + " of the " +
           std::to_string(matches);
    if (direction.norm() > 0.5)
      s += "; moved " + directionWords(direction) + " (" + fixed(direction.x(), 2) + ", " +
           fixed(direction.y(), 2) + ", " + fixed(direction.z(), 2) + ")";
  }
  return s;
}

TwoViewMotionEstimator::TwoViewMotionEstimator(PinholeCamera camera, UnpreparedMapParams params)
    : camera_(std::move(camera)), params_(std::move(params)) {
  camera_.check();
  params_.check();
}

TwoViewKeyframe TwoViewMotionEstimator::describe(const cv::Mat& image) const {
  if (image.empty() || image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
    throw Error("two-view motion: the image must be 8-bit grey or BGR");
  if (image.size() != camera_.imageSize())
    throw Error("two-view motion: the image is " + std::to_string(image.cols) + "x" +
                std::to_string(image.rows) + " but the camera is for " +
                std::to_string(camera_.imageSize().width) + "x" +
                std::to_string(camera_.imageSize().height) + " images");
  TwoViewKeyframe k;
  KeypointFeatures(params_.keypoints)
      .detectAndDescribe(image, params_.maxKeypoints, k.keypoints, k.descriptors);
  std::vector<cv::Point2f> pixels;
  for (const cv::KeyPoint& p : k.keypoints) pixels.push_back(p.pt);
  if (!pixels.empty()) k.undistorted = camera_.undistortPixels(pixels);
  return k;
}

std::string TwoViewMotionEstimator::texturelessRefusal(const TwoViewKeyframe& view,
                                                       const std::string& which) const {
  const int n = static_cast<int>(view.keypoints.size());
  if (n >= params_.minKeypoints) return {};
  return "the " + which + " view is textureless: " + std::to_string(n) + " " + params_.keypoints +
         " keypoints (at least " + std::to_string(params_.minKeypoints) +
         " needed); point the camera at a textured part of the scene (not a blank wall, not in "
         "the dark, not blurred)";
}

TwoViewMotion TwoViewMotionEstimator::estimate(const TwoViewKeyframe& first,
                                               const TwoViewKeyframe& second) const {
  const UnpreparedMapParams& p = params_;
  TwoViewMotion m;
  m.keypointsFirst = static_cast<int>(first.keypoints.size());
  m.keypointsSecond = static_cast<int>(second.keypoints.size());
  m.refusal = texturelessRefusal(first, "first");
  if (m.refusal.empty()) m.refusal = texturelessRefusal(second, "second");
  if (!m.refusal.empty()) return m;
  const std::vector<cv::DMatch> matches =
      matchDescriptors(first.descriptors, second.descriptors,
                       KeypointFeatures(p.keypoints).normType(), p.ratio, true);
  m.matches = static_cast<int>(matches.size());
  if (m.matches < p.minMatches) {
    m.refusal = "the two views share too little: " + std::to_string(m.matches) +
                " keypoint matches (at least " + std::to_string(p.minMatches) +
                " needed); keep most of the same scene in view when you move";
    return m;
  }
  std::vector<cv::Point2f> a, b;
  for (const cv::DMatch& d : matches) {
    a.push_back(first.undistorted[static_cast<std::size_t>(d.queryIdx)]);
    b.push_back(second.undistorted[static_cast<std::size_t>(d.trainIdx)]);
  }
  cv::Mat K;
  cv::eigen2cv(camera_.K(), K);
  cv::Mat ransacMask;
  const cv::Mat E =
      cv::findEssentialMat(a, b, K, cv::RANSAC, 0.999, p.ransacThresholdPx, ransacMask);
  std::vector<std::size_t> ransacInliers;
  if (!E.empty() && E.rows == 3 && E.cols == 3)
    for (std::size_t i = 0; i < a.size(); ++i)
      if (ransacMask.at<unsigned char>(static_cast<int>(i))) ransacInliers.push_back(i);
  m.inliers = static_cast<int>(ransacInliers.size());
  if (m.inliers < p.minInliers) {
    m.refusal = "the keypoint matches fit no camera motion: " + std::to_string(m.inliers) + " of " +
                std::to_string(m.matches) + " fit the essential matrix (at least " +
                std::to_string(p.minInliers) +
                " needed); is it the same scene, still, and the camera's calibration?";
    return m;
  }

  // A rotation alone: fitted to the inliers' rays, refitted twice to those it explains within
  // twice the threshold (the fit to all of them is pulled by the parallax of a real move).
  const Eigen::Matrix3d& Km = camera_.K();
  const Eigen::Matrix3d Kinv = Km.inverse();
  std::vector<Eigen::Vector3d> ra, rb;
  for (std::size_t i : ransacInliers) {
    ra.push_back(rayOf(Kinv, a[i]));
    rb.push_back(rayOf(Kinv, b[i]));
  }
  Eigen::Matrix3d Rrot = rotationBetween(ra, rb);
  for (int round = 0; round < 2; ++round) {
    std::vector<Eigen::Vector3d> fa, fb;
    for (std::size_t k = 0; k < ra.size(); ++k)
      if (rotatedDistancePx(Km, Rrot, ra[k], b[ransacInliers[k]]) <= 2.0 * p.ransacThresholdPx) {
        fa.push_back(ra[k]);
        fb.push_back(rb[k]);
      }
    if (fa.size() < 3) break;
    Rrot = rotationBetween(fa, fb);
  }
  for (std::size_t k = 0; k < ra.size(); ++k)
    m.rotationInliers +=
        rotatedDistancePx(Km, Rrot, ra[k], b[ransacInliers[k]]) <= p.ransacThresholdPx ? 1 : 0;
  m.rotationShare = static_cast<double>(m.rotationInliers) / m.inliers;
  if (m.rotationShare >= p.maxRotationShare) {
    m.refusal = "the camera turned but hardly moved: a rotation alone explains " +
                fixed(100.0 * m.rotationShare, 0) + "% of the " + std::to_string(m.inliers) +
                " matches (at most " + fixed(100.0 * p.maxRotationShare, 0) +
                "% allowed), so nothing can be triangulated; move the camera sideways (about a "
                "tenth of its distance to the scene) instead of turning it on the spot";
    return m;
  }

  // The essential matrix's motion (cheirality: the points in front of both cameras).
  cv::Mat R, t, poseMask = ransacMask.clone();
  cv::recoverPose(E, a, b, K, R, t, poseMask);
  Eigen::Matrix3d Re;
  Eigen::Vector3d te;
  cv::cv2eigen(R, Re);
  cv::cv2eigen(t, te);
  if (!Re.allFinite() || !te.allFinite() || !(te.norm() > 0.5)) {
    m.refusal = "the essential matrix gives no motion; move the camera sideways and try again";
    return m;
  }
  te.normalize();
  m.firstToSecond = RigidPose(Re, te);
  m.direction = m.firstToSecond.cameraCentre();
  std::vector<double> angles, pixels;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!poseMask.at<unsigned char>(static_cast<int>(i))) continue;
    const Eigen::Vector3d ray = rayOf(Kinv, a[i]);
    const double cosine = std::clamp(rayOf(Kinv, b[i]).dot(Re * ray), -1.0, 1.0);
    angles.push_back(std::acos(cosine) * kRadToDeg);
    pixels.push_back(rotatedDistancePx(Km, Re, ray, b[i]));
    m.inlierFirst.push_back(a[i]);
    m.inlierSecond.push_back(b[i]);
  }
  const int inFront = static_cast<int>(angles.size());
  if (inFront < p.minInliers) {
    // No motion puts the points in front: a move too small for the essential matrix to tell
    // (on a plane it is then ambiguous). The parallax a rotation does not explain says how
    // small.
    std::vector<double> residual;
    for (std::size_t k = 0; k < ra.size(); ++k)
      residual.push_back(std::acos(std::clamp(rb[k].dot(Rrot * ra[k]), -1.0, 1.0)) * kRadToDeg);
    m.medianParallaxDeg = median(residual);
    m.medianParallaxPx = m.medianParallaxDeg / kRadToDeg * camera_.fx();
    if (m.medianParallaxDeg < p.minParallaxDeg) {
      m.refusal = "too little parallax: beyond a rotation, the scene is seen " +
                  fixed(m.medianParallaxDeg, 2) + " deg apart from the two places (about " +
                  fixed(m.medianParallaxPx, 1) + " px, median; at least " +
                  fixed(p.minParallaxDeg, 2) + " deg needed); move the camera farther sideways";
      return m;
    }
    m.refusal = "the camera hardly moved: the motion the matches give puts only " +
                std::to_string(inFront) + " of the " + std::to_string(m.inliers) +
                " in front of both cameras (at least " + std::to_string(p.minInliers) +
                " needed); move the camera sideways (about a tenth of its distance to the scene) "
                "and try again";
    return m;
  }
  m.inliers = inFront;
  // The plane's homography and its decompositions (the motions with the plane in front).
  cv::Mat homographyMask;
  const cv::Mat H = cv::findHomography(a, b, cv::RANSAC, p.ransacThresholdPx, homographyMask);
  if (!H.empty()) {
    m.homographyInliers = cv::countNonZero(homographyMask);
    std::vector<cv::Mat> rotations, translations, normals;
    cv::decomposeHomographyMat(H, K, rotations, translations, normals);
    // The visibility test takes normalised (rectified) image points.
    std::vector<cv::Point2f> planeFirst, planeSecond;
    const auto normalised = [&](const cv::Point2f& q) {
      const Eigen::Vector3d r = Kinv * Eigen::Vector3d(q.x, q.y, 1.0);
      return cv::Point2f(static_cast<float>(r.x()), static_cast<float>(r.y()));
    };
    for (std::size_t i = 0; i < a.size(); ++i)
      if (homographyMask.at<unsigned char>(static_cast<int>(i))) {
        planeFirst.push_back(normalised(a[i]));
        planeSecond.push_back(normalised(b[i]));
      }
    std::vector<int> visible;
    cv::filterHomographyDecompByVisibleRefpoints(rotations, normals, planeFirst, planeSecond,
                                                 visible);
    for (int i : visible) {
      Eigen::Matrix3d Rh;
      Eigen::Vector3d th;
      cv::cv2eigen(rotations[static_cast<std::size_t>(i)], Rh);
      cv::cv2eigen(translations[static_cast<std::size_t>(i)], th);
      if (Rh.allFinite() && th.allFinite() && th.norm() > 1e-9)
        m.planeMotions.emplace_back(Rh, th.normalized());
    }
  }
  m.medianParallaxDeg = median(angles);
  m.medianParallaxPx = median(pixels);
  if (m.medianParallaxDeg < p.minParallaxDeg) {
    m.refusal = "too little parallax: the scene is seen " + fixed(m.medianParallaxDeg, 2) +
                " deg apart from the two places (" + fixed(m.medianParallaxPx, 1) +
                " px, median; at least " + fixed(p.minParallaxDeg, 2) +
                " deg needed); move the camera farther sideways";
    return m;
  }
  return m;
}

}  // namespace reftrack
