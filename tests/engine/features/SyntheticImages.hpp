#pragma once
// Synthetic test images with exact ground truth: a textured scene of random rectangles and
// ellipses on a smooth background, ideal squares with known sub-pixel corners, and warps of an
// image by a known homography.
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace reftrack::test {

// Random rectangles and ellipses (grey levels 20..235) over a smooth gradient, slightly blurred.
inline cv::Mat texturedImage(cv::Size size, uint64_t seed, int shapes = 0) {
  cv::RNG rng(seed);
  cv::Mat img(size, CV_8UC1);
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x)
      img.at<uchar>(y, x) = static_cast<uchar>(90 + 40.0 * x / size.width + 30.0 * y / size.height);
  if (shapes == 0) shapes = size.area() / 600;
  for (int i = 0; i < shapes; ++i) {
    const cv::Point c(rng.uniform(0, size.width), rng.uniform(0, size.height));
    const int w = rng.uniform(4, std::max(6, size.width / 12));
    const int h = rng.uniform(4, std::max(6, size.height / 12));
    const cv::Scalar grey(rng.uniform(20, 236));
    if (rng.uniform(0, 3) == 0)
      cv::ellipse(img, c, cv::Size(w / 2, h / 2), rng.uniform(0, 180), 0, 360, grey, cv::FILLED,
                  cv::LINE_AA);
    else
      cv::rectangle(img, cv::Rect(c.x, c.y, w, h), grey, cv::FILLED);
  }
  cv::GaussianBlur(img, img, cv::Size(0, 0), 0.7);
  return img;
}

// dst(x) = src(H^-1 x): the image as seen through the homography H (src -> dst).
inline cv::Mat warpedBy(const cv::Mat& src, const cv::Matx33d& H, cv::Size size = {}) {
  cv::Mat dst;
  cv::warpPerspective(src, dst, H, size.area() ? size : src.size(), cv::INTER_LINEAR,
                      cv::BORDER_REFLECT);
  return dst;
}

inline cv::Mat withNoise(const cv::Mat& src, double sigma, uint64_t seed) {
  cv::Mat noise(src.size(), CV_32F), f;
  cv::RNG(seed).fill(noise, cv::RNG::NORMAL, 0, sigma);
  src.convertTo(f, CV_32F);
  f += noise;
  cv::Mat out;
  f.convertTo(out, CV_8U);
  return out;
}

// Max distance over the four image corners between H and the truth (pixels).
inline double cornerError(const cv::Matx33d& H, const cv::Matx33d& truth, cv::Size size) {
  double worst = 0;
  for (const cv::Point2d p :
       {cv::Point2d(0, 0), cv::Point2d(size.width - 1, 0), cv::Point2d(0, size.height - 1),
        cv::Point2d(size.width - 1, size.height - 1)}) {
    const cv::Vec3d a = H * cv::Vec3d(p.x, p.y, 1), b = truth * cv::Vec3d(p.x, p.y, 1);
    worst = std::max(worst, std::hypot(a[0] / a[2] - b[0] / b[2], a[1] / a[2] - b[1] / b[2]));
  }
  return worst;
}

// A far view of a planar image filling `size` (focal length = width): the plane tilted out of
// the image by tiltDeg about its vertical axis through the centre, seen at `scale` (distance
// f / scale) and rotated in-plane by rollDeg. Reference pixels -> view pixels, h33 = 1.
inline cv::Matx33d tiltedView(cv::Size size, double tiltDeg, double scale, double rollDeg) {
  const double pi = 3.14159265358979323846;
  const double f = size.width, cx = (size.width - 1) / 2.0, cy = (size.height - 1) / 2.0;
  const cv::Matx33d K(f, 0, cx, 0, f, cy, 0, 0, 1);
  const double t = tiltDeg * pi / 180.0, r = rollDeg * pi / 180.0;
  const cv::Matx33d Ry(std::cos(t), 0, std::sin(t), 0, 1, 0, -std::sin(t), 0, std::cos(t));
  const cv::Matx33d Rz(std::cos(r), -std::sin(r), 0, std::sin(r), std::cos(r), 0, 0, 0, 1);
  const cv::Matx33d R = Rz * Ry;
  // Plane point (x, y) (pixels from the centre) at R (x, y, 0) + (0, 0, f / scale).
  const cv::Matx33d P(R(0, 0), R(0, 1), 0, R(1, 0), R(1, 1), 0, R(2, 0), R(2, 1), f / scale);
  const cv::Matx33d toPlane(1, 0, -cx, 0, 1, -cy, 0, 0, 1);
  const cv::Matx33d H = K * P * toPlane;
  return H * (1.0 / H(2, 2));
}

// A brick wall in running bond (a repeated pattern): bricks of brickW x brickH pixels (joint
// `joint` px, light mortar), each brick its own grey level (in [70, 70 + shades)) with up to
// `speckles` darker and lighter speckles, slightly blurred. Near-duplicates everywhere: every
// brick corner looks alike.
inline cv::Mat brickWallImage(cv::Size size, uint64_t seed, int brickW = 48, int brickH = 16,
                              int joint = 3, int speckles = 3, int shades = 50) {
  cv::RNG rng(seed);
  cv::Mat img(size, CV_8UC1, cv::Scalar(190));
  for (int row = 0, y = 0; y < size.height; ++row, y += brickH + joint) {
    const int shift = (row % 2) * (brickW + joint) / 2;
    for (int x = -shift; x < size.width; x += brickW + joint) {
      const cv::Rect brick(x, y, brickW, brickH);
      cv::rectangle(img, brick, cv::Scalar(rng.uniform(70, 70 + shades)), cv::FILLED);
      for (int k = rng.uniform(0, speckles + 1); k > 0; --k)
        cv::circle(img, cv::Point(x + rng.uniform(2, brickW - 2), y + rng.uniform(2, brickH - 2)),
                   rng.uniform(1, 3), cv::Scalar(rng.uniform(0, 2) ? 50 : 140), cv::FILLED,
                   cv::LINE_AA);
    }
  }
  cv::GaussianBlur(img, img, cv::Size(0, 0), 0.7);
  return img;
}

}  // namespace reftrack::test
