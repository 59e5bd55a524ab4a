#include "app/research/homography/HomographyGroundTruth.hpp"

#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "engine/homography/HomographyDlt.hpp"

namespace reftrack::app {

namespace {

bool inside(cv::Point2d p, cv::Size size) {
  return p.x >= -0.5 && p.y >= -0.5 && p.x <= size.width - 0.5 && p.y <= size.height - 0.5;
}

// Applies H and reports whether the point lies in front of the camera (w > 0 for the
// rotation homographies used here: K R K^-1 maps a ray behind the frame camera to w < 0).
bool mapInFront(const cv::Matx33d& H, cv::Point2d p, cv::Point2d& q) {
  const double w = H(2, 0) * p.x + H(2, 1) * p.y + H(2, 2);
  if (!(w > 1e-12)) return false;
  q = transferPoint(H, p);
  return std::isfinite(q.x) && std::isfinite(q.y);
}

}  // namespace

cv::Matx33d rotationHomography(const Eigen::Matrix3d& K, const Eigen::Matrix3d& R) {
  const Eigen::Matrix3d H = K * R * K.inverse();
  cv::Matx33d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = H(r, c) / H(2, 2);
  return out;
}

double overlapFraction(const cv::Matx33d& trueH, cv::Size size) {
  const cv::Matx33d inv = trueH.inv();
  constexpr int kCols = 64, kRows = 48;
  int seen = 0;
  for (int j = 0; j < kRows; ++j)
    for (int i = 0; i < kCols; ++i) {
      const cv::Point2d c((i + 0.5) * size.width / kCols - 0.5,
                          (j + 0.5) * size.height / kRows - 0.5);
      cv::Point2d r;
      if (mapInFront(inv, c, r) && inside(r, size)) ++seen;
    }
  return static_cast<double>(seen) / (kCols * kRows);
}

double meanTransferDeviation(const cv::Matx33d& estimatedH, const cv::Matx33d& trueH,
                             const std::vector<cv::Point2d>& referencePoints, cv::Size size) {
  double sum = 0;
  int n = 0;
  for (const cv::Point2d& p : referencePoints) {
    cv::Point2d truth;
    if (!mapInFront(trueH, p, truth) || !inside(truth, size)) continue;
    const cv::Point2d est = transferPoint(estimatedH, p);
    const double e = std::hypot(est.x - truth.x, est.y - truth.y);
    sum += std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
    ++n;
  }
  return n > 0 ? sum / n : std::numeric_limits<double>::quiet_NaN();
}

double frameCornerError(const cv::Matx33d& estimatedH, const cv::Matx33d& trueH, cv::Size size) {
  const cv::Matx33d inv = trueH.inv();
  const double w = size.width - 1.0, h = size.height - 1.0;
  double sum = 0;
  for (const cv::Point2d c :
       {cv::Point2d(0, 0), cv::Point2d(w, 0), cv::Point2d(w, h), cv::Point2d(0, h)}) {
    const cv::Point2d est = transferPoint(estimatedH, transferPoint(inv, c));
    const double e = std::hypot(est.x - c.x, est.y - c.y);
    sum += std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
  }
  return sum / 4.0;
}

double referenceCornerError(const cv::Matx33d& estimatedH, const cv::Matx33d& trueH,
                            cv::Size referenceSize) {
  const double w = referenceSize.width - 1.0, h = referenceSize.height - 1.0;
  double sum = 0;
  for (const cv::Point2d c :
       {cv::Point2d(0, 0), cv::Point2d(w, 0), cv::Point2d(w, h), cv::Point2d(0, h)}) {
    const cv::Point2d est = transferPoint(estimatedH, c), truth = transferPoint(trueH, c);
    const double e = std::hypot(est.x - truth.x, est.y - truth.y);
    sum += std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
  }
  return sum / 4.0;
}

std::vector<cv::Point2d> annotationGrid(cv::Size size, int cols, int rows) {
  std::vector<cv::Point2d> out;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i)
      out.emplace_back((i + 0.5) * size.width / cols - 0.5, (j + 0.5) * size.height / rows - 0.5);
  return out;
}

}  // namespace reftrack::app
