#pragma once
// Shared synthetic images for the tracking tests: a seeded, non-repetitive texture of random
// rotated rectangles and blobs (rich in corners of many contrasts), and its exact warp.
#include <opencv2/imgproc.hpp>

namespace reftrack::test {

inline cv::Mat texturedImage(cv::Size size, int seed) {
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  cv::Mat img(size, CV_8UC1, cv::Scalar(128));
  for (int i = 0; i < 900; ++i) {
    const cv::Point2f c(rng.uniform(0.f, static_cast<float>(size.width)),
                        rng.uniform(0.f, static_cast<float>(size.height)));
    const cv::Size2f s(rng.uniform(6.f, 40.f), rng.uniform(6.f, 40.f));
    const cv::RotatedRect rect(c, s, rng.uniform(0.f, 180.f));
    cv::Point2f pts[4];
    rect.points(pts);
    std::vector<cv::Point> poly;
    for (const cv::Point2f& p : pts)
      poly.emplace_back(cv::Point(cvRound(p.x * 16), cvRound(p.y * 16)));
    cv::fillConvexPoly(img, poly, cv::Scalar(rng.uniform(0, 256)), cv::LINE_AA, 4);
  }
  cv::GaussianBlur(img, img, cv::Size(3, 3), 0.7);
  return img;
}

// The image seen through homography G (source -> destination), bilinear, border replicated.
inline cv::Mat warped(const cv::Mat& img, const cv::Matx33d& G) {
  cv::Mat out;
  cv::warpPerspective(img, out, cv::Mat(G), img.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return out;
}

inline cv::Point2d applyH(const cv::Matx33d& G, cv::Point2d p) {
  const cv::Vec3d q = G * cv::Vec3d(p.x, p.y, 1.0);
  return {q[0] / q[2], q[1] / q[2]};
}

// A strong viewpoint change about the image centre: rotation, scale, shear and perspective.
inline cv::Matx33d strongWarp(cv::Size size, double angleDeg, double scale) {
  const double a = angleDeg * CV_PI / 180.0;
  const double cx = size.width / 2.0, cy = size.height / 2.0;
  const cv::Matx33d T1(1, 0, -cx, 0, 1, -cy, 0, 0, 1), T2(1, 0, cx, 0, 1, cy, 0, 0, 1);
  const cv::Matx33d R(scale * std::cos(a), -scale * std::sin(a), 0, scale * std::sin(a),
                      scale * std::cos(a), 0, 0.0004, 0.0002, 1);
  return T2 * R * T1;
}

}  // namespace reftrack::test
