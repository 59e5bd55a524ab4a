#include "engine/features/RmsContrast.hpp"

#include <cmath>

#include "engine/core/Error.hpp"

namespace reftrack {

double rmsContrast(const cv::Mat& gray, cv::Point2f centre, int window) {
  if (gray.empty() || gray.type() != CV_8UC1)
    throw Error("rmsContrast: expected a non-empty 8-bit grey image");
  if (window < 1 || window % 2 == 0) throw Error("rmsContrast: window must be odd and positive");
  const int h = window / 2;
  const int cx = static_cast<int>(std::lround(centre.x));
  const int cy = static_cast<int>(std::lround(centre.y));
  const int x0 = std::max(0, cx - h), x1 = std::min(gray.cols - 1, cx + h);
  const int y0 = std::max(0, cy - h), y1 = std::min(gray.rows - 1, cy + h);
  if (x0 > x1 || y0 > y1) return 0.0;
  // Integer sums are exact for 8-bit windows up to 101x101.
  long long sum = 0, sumSq = 0;
  for (int y = y0; y <= y1; ++y) {
    const uchar* row = gray.ptr<uchar>(y);
    for (int x = x0; x <= x1; ++x) {
      sum += row[x];
      sumSq += row[x] * row[x];
    }
  }
  const double n = static_cast<double>((x1 - x0 + 1) * (y1 - y0 + 1));
  const double mean = sum / n;
  return std::sqrt(std::max(0.0, sumSq / n - mean * mean));
}

}  // namespace reftrack
