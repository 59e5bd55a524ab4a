#include "engine/matching/DistinctiveCorners.hpp"

#include <cmath>

#include "engine/core/Error.hpp"
#include "engine/features/CornerGrid.hpp"
#include "engine/matching/NccCorrelation.hpp"

namespace reftrack {

std::vector<char> distinctiveCorners(const cv::Mat& gray, const std::vector<cv::Point2f>& corners,
                                     int halfWindow, double radius, double maxTwinScore) {
  if (gray.empty() || gray.type() != CV_8UC1)
    throw Error("distinctive corners: the image must be 8-bit grey");
  if (halfWindow < 1 || !(radius > 0)) throw Error("distinctive corners: bad window or radius");
  std::vector<char> out(corners.size(), 0);
  if (corners.empty()) return out;
  const NccPatches windows = NccPatches::square(gray, corners, halfWindow);
  const CornerGrid grid(corners, gray.size(), std::max(8, static_cast<int>(radius / 2)));
  std::vector<int> nearby;
  const double r2 = radius * radius;
  // Windows that overlap by more than half are one structure seen twice, not a repeat.
  const double overlap2 = 4.0 * halfWindow * halfWindow;
  for (int i = 0; i < static_cast<int>(corners.size()); ++i) {
    if (!windows.valid(i)) continue;
    const cv::Point2f& p = corners[static_cast<std::size_t>(i)];
    grid.query(cv::Point2d(p), radius, radius, nearby);
    bool twin = false;
    for (int j : nearby) {
      if (j == i || !windows.valid(j)) continue;
      const cv::Point2f d = corners[static_cast<std::size_t>(j)] - p;
      if (d.dot(d) > r2 || d.dot(d) < overlap2) continue;
      if (windows.score(i, windows, j) > maxTwinScore) {
        twin = true;
        break;
      }
    }
    out[static_cast<std::size_t>(i)] = twin ? 0 : 1;
  }
  return out;
}

}  // namespace reftrack
