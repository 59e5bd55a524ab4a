#include "engine/geometry/PinholeCamera.hpp"

#include <cmath>
#include <fstream>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <sstream>

#include "engine/config/ConfigFile.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/config/YamlMatrix.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

std::string where(const std::filesystem::path& file) {
  return "camera file '" + file.string() + "'";
}

cv::TermCriteria exactUndistortion() {
  // cv::undistortPoints stops after 5 fixed-point iterations, which leaves 0.17 px at the corners
  // of a 50-degree 640x480 camera with k1 = -0.3 (PinholeCamera_test; the iteration contracts by
  // only ~0.3 per step there). OpenCV's EPS test is the reprojection error in pixels, so this
  // stops once the point re-distorts to within 1e-4 px.
  return {cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-4};
}

// The keys a camera file may hold: ours, then the records OpenCV's calibration samples
// (samples/cpp/calibration.cpp, the camera_calibration tutorial, aruco's
// calibrate_camera_charuco) write beside the intrinsics, which are accepted and ignored.
const std::vector<std::string> kCameraFileKeys = {"image_width",
                                                  "image_height",
                                                  "camera_matrix",
                                                  "distortion_coefficients",
                                                  "calibration_time",
                                                  "nframes",
                                                  "nr_of_frames",
                                                  "board_width",
                                                  "board_height",
                                                  "square_size",
                                                  "marker_size",
                                                  "aspectRatio",
                                                  "fix_aspect_ratio",
                                                  "flags",
                                                  "fisheye_model",
                                                  "avg_reprojection_error",
                                                  "per_view_reprojection_errors",
                                                  "extrinsic_parameters",
                                                  "image_points",
                                                  "grid_points"};

}  // namespace

PinholeCamera::PinholeCamera(const Eigen::Matrix3d& K, cv::Size imageSize,
                             std::vector<double> distortion)
    : K_(K), size_(imageSize), dist_(std::move(distortion)) {}

PinholeCamera PinholeCamera::fromFieldOfView(cv::Size imageSize, double horizontalFovDeg) {
  if (!(horizontalFovDeg > 0.0 && horizontalFovDeg < 180.0))
    throw Error("field of view must be in (0, 180) degrees, got " +
                std::to_string(horizontalFovDeg));
  const double f =
      0.5 * imageSize.width / std::tan(0.5 * horizontalFovDeg * std::numbers::pi / 180.0);
  Eigen::Matrix3d K;
  K << f, 0, (imageSize.width - 1) * 0.5, 0, f, (imageSize.height - 1) * 0.5, 0, 0, 1;
  PinholeCamera cam(K, imageSize);
  cam.check();
  return cam;
}

cv::Matx33d PinholeCamera::Kcv() const {
  cv::Matx33d k;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) k(r, c) = K_(r, c);
  return k;
}

bool PinholeCamera::hasDistortion() const {
  for (double d : dist_)
    if (d != 0.0) return true;
  return false;
}

void PinholeCamera::check() const {
  if (size_.width <= 0 || size_.height <= 0)
    throw Error("image_width and image_height must be positive, got " +
                std::to_string(size_.width) + "x" + std::to_string(size_.height));
  if (!K_.allFinite()) throw Error("camera_matrix contains NaN or infinity");
  if (!(fx() > 0.0)) throw Error("camera_matrix: focal length fx must be positive");
  if (!(fy() > 0.0)) throw Error("camera_matrix: focal length fy must be positive");
  if (K_(1, 0) != 0.0 || K_(2, 0) != 0.0 || K_(2, 1) != 0.0 || K_(2, 2) != 1.0)
    throw Error("camera_matrix must have the form [fx s cx; 0 fy cy; 0 0 1]");
  if (cx() < -0.5 || cx() > size_.width - 0.5 || cy() < -0.5 || cy() > size_.height - 0.5)
    throw Error("camera_matrix: principal point lies outside the image");
  static const std::vector<size_t> allowed = {0, 4, 5, 8, 12, 14};
  if (std::find(allowed.begin(), allowed.end(), dist_.size()) == allowed.end())
    throw Error("distortion_coefficients must have 4, 5, 8, 12 or 14 entries, got " +
                std::to_string(dist_.size()));
  for (double d : dist_)
    if (!std::isfinite(d)) throw Error("distortion_coefficients contain NaN or infinity");
}

PinholeCamera PinholeCamera::load(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw Error(where(file) + " does not exist");
  const YamlNode root = readConfigFile(file, where(file));
  PinholeCamera cam;
  try {
    requireKnownKeys(root, kCameraFileKeys);
    const auto requireNode = [&](const char* key) {
      const YamlNode n = root[key];
      if (!n.present()) throw Error("missing key '" + std::string(key) + "'");
      return n;
    };
    const YamlNode w = requireNode("image_width"), h = requireNode("image_height");
    for (const YamlNode& n : {w, h})
      if (!n.integer()) n.fail("image_width and image_height must be integers");
    cam.size_ = cv::Size(*w.integer(), *h.integer());
    const YamlNode kn = requireNode("camera_matrix");
    cv::Mat K = readYamlMatrix(kn);
    if (K.rows != 3 || K.cols != 3 || K.channels() != 1)
      kn.fail("camera_matrix must be a 3x3 matrix");
    K.convertTo(K, CV_64F);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) cam.K_(r, c) = K.at<double>(r, c);
    const YamlNode dn = root["distortion_coefficients"];
    if (dn.present()) {
      cv::Mat D = readYamlMatrix(dn);
      if (!D.empty()) {
        if ((D.rows != 1 && D.cols != 1) || D.channels() != 1)
          dn.fail("distortion_coefficients must be a vector");
        D.convertTo(D, CV_64F);
        D = D.reshape(1, 1);
        cam.dist_.assign(D.ptr<double>(), D.ptr<double>() + D.cols);
      }
    }
    cam.check();
  } catch (const Error& e) {
    throw Error(where(file) + ": " + e.what());
  }
  return cam;
}

void PinholeCamera::save(const std::filesystem::path& file) const {
  check();
  writeFileAtomically(file, [&](const std::filesystem::path& tmp) {
    cv::FileStorage fs(tmp.string(), cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
    fs << "image_width" << size_.width << "image_height" << size_.height;
    fs << "camera_matrix" << cv::Mat(Kcv());
    cv::Mat D = dist_.empty() ? cv::Mat::zeros(5, 1, CV_64F) : cv::Mat(dist_, true);
    fs << "distortion_coefficients" << D.reshape(1, static_cast<int>(D.total()));
    fs.release();
  });
}

Eigen::Vector2d PinholeCamera::project(const Eigen::Vector3d& X) const {
  Eigen::Vector3d p = K_ * X;
  return p.head<2>() / p.z();
}

Eigen::Vector2d PinholeCamera::projectDistorted(const Eigen::Vector3d& X) const {
  if (!hasDistortion()) return project(X);
  std::vector<cv::Point3d> obj{{X.x(), X.y(), X.z()}};
  std::vector<cv::Point2d> img;
  cv::projectPoints(obj, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), Kcv(), dist_, img);
  return {img[0].x, img[0].y};
}

std::vector<cv::Point2f> PinholeCamera::undistortPixels(
    const std::vector<cv::Point2f>& pixels) const {
  if (!hasDistortion() || pixels.empty()) return pixels;
  std::vector<cv::Point2f> out;
  cv::undistortPoints(pixels, out, Kcv(), dist_, cv::noArray(), Kcv(), exactUndistortion());
  return out;
}

PinholeCamera PinholeCamera::scaled(double s) const {
  Eigen::Matrix3d K = K_;
  K(0, 0) *= s;
  K(1, 1) *= s;
  K(0, 1) *= s;
  K(0, 2) = (K_(0, 2) + 0.5) * s - 0.5;
  K(1, 2) = (K_(1, 2) + 0.5) * s - 0.5;
  return PinholeCamera(K,
                       cv::Size(static_cast<int>(std::lround(size_.width * s)),
                                static_cast<int>(std::lround(size_.height * s))),
                       dist_);
}

}  // namespace reftrack
