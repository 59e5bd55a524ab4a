#include "app/research/homography/SyntheticViews.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"

namespace reftrack::app {

cv::Matx33d syntheticViewHomography(cv::Size size, double tiltDeg, double azimuthDeg, double scale,
                                    double rollDeg) {
  constexpr double kPi = std::numbers::pi;
  const double f = size.width, cx = (size.width - 1) / 2.0, cy = (size.height - 1) / 2.0;
  Eigen::Matrix3d K;
  K << f, 0, cx, 0, f, cy, 0, 0, 1;
  // Plane z = 0 in pixel units centred on the image; the reference camera sits at distance f.
  Eigen::Matrix3d reference;
  reference << 1, 0, 0, 0, 1, 0, 0, 0, f;
  const double a = azimuthDeg * kPi / 180.0;
  const Eigen::Matrix3d cameraToWorld =
      Eigen::AngleAxisd(tiltDeg * kPi / 180.0, Eigen::Vector3d(std::cos(a), std::sin(a), 0))
          .toRotationMatrix() *
      Eigen::AngleAxisd(rollDeg * kPi / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d centre = -(f / scale) * cameraToWorld.col(2);
  const Eigen::Matrix3d R = cameraToWorld.transpose();
  Eigen::Matrix3d view;
  view.col(0) = R.col(0);
  view.col(1) = R.col(1);
  view.col(2) = -R * centre;
  const Eigen::Matrix3d He = K * view * (K * reference).inverse();
  cv::Matx33d H;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) H(r, c) = He(r, c) / He(2, 2);
  return H;
}

cv::Mat synthesiseView(const cv::Mat& image, const cv::Matx33d& H, double noiseSigma,
                       std::uint64_t seed, cv::Size frameSize, int border) {
  if (image.empty()) throw Error("synthesise view: the image is empty");
  const cv::Size size = frameSize.area() > 0 ? frameSize : image.size();
  // Twice the resolution: x2 = 2 x1 + 0.5 (pixel centres), then area-averaged back down.
  const cv::Matx33d up(2, 0, 0.5, 0, 2, 0.5, 0, 0, 1);
  cv::Mat big, out;
  cv::warpPerspective(image, big, up * H, size * 2, cv::INTER_LINEAR, border, cv::Scalar::all(0));
  cv::resize(big, out, size, 0, 0, cv::INTER_AREA);
  if (noiseSigma > 0) {  // Gaussian sensor noise, deterministic in seed
    cv::Mat noise(out.size(), CV_32FC(out.channels())), noisy;
    cv::RNG(seed).fill(noise, cv::RNG::NORMAL, 0.0, noiseSigma);
    out.convertTo(noisy, noise.type());
    noisy += noise;
    noisy.convertTo(out, image.type());
  }
  return out;
}

cv::Mat relight(const cv::Mat& image, double gain, double offset, cv::Vec2d gradient) {
  if (image.empty() || image.depth() != CV_8U) throw Error("relight: expected an 8-bit image");
  const double cx = (image.cols - 1) / 2.0, cy = (image.rows - 1) / 2.0;
  const double half = std::hypot(cx, cy) > 0 ? std::hypot(cx, cy) : 1.0;
  cv::Mat light(image.size(), CV_32F);
  for (int y = 0; y < image.rows; ++y) {
    auto* row = light.ptr<float>(y);
    for (int x = 0; x < image.cols; ++x)
      row[x] = static_cast<float>(
          gain * std::max(0.0, 1.0 + (gradient[0] * (x - cx) + gradient[1] * (y - cy)) / half));
  }
  cv::Mat value, lit;
  image.convertTo(value, CV_32F);
  if (image.channels() > 1) cv::merge(std::vector<cv::Mat>(image.channels(), light), light);
  cv::multiply(value, light, lit);
  lit += cv::Scalar::all(offset);
  cv::Mat out;
  lit.convertTo(out, image.type());
  return out;
}

}  // namespace reftrack::app
