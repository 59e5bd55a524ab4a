#include "engine/features/CornerGrid.hpp"

#include <algorithm>
#include <cmath>

#include "engine/core/Error.hpp"

namespace reftrack {

CornerGrid::CornerGrid(const std::vector<cv::Point2f>& points, cv::Size imageSize, int cellSize)
    : cell_(std::max(1, cellSize)) {
  if (imageSize.width <= 0 || imageSize.height <= 0) throw Error("CornerGrid: empty image size");
  cols_ = (imageSize.width + cell_ - 1) / cell_;
  rows_ = (imageSize.height + cell_ - 1) / cell_;
  const auto cellOf = [&](const cv::Point2f& p) {
    const int cx = std::clamp(static_cast<int>(p.x) / cell_, 0, cols_ - 1);
    const int cy = std::clamp(static_cast<int>(p.y) / cell_, 0, rows_ - 1);
    return static_cast<std::size_t>(cy * cols_ + cx);
  };
  // Counting sort by cell (stable: index order within a cell).
  cellStart_.assign(static_cast<std::size_t>(cols_ * rows_) + 1, 0);
  for (const cv::Point2f& p : points) ++cellStart_[cellOf(p) + 1];
  for (std::size_t i = 1; i < cellStart_.size(); ++i) cellStart_[i] += cellStart_[i - 1];
  sorted_.resize(points.size());
  sortedIndex_.resize(points.size());
  std::vector<int> next(cellStart_.begin(), cellStart_.end() - 1);
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    const cv::Point2f& p = points[static_cast<std::size_t>(i)];
    const std::size_t slot = static_cast<std::size_t>(next[cellOf(p)]++);
    sorted_[slot] = p;
    sortedIndex_[slot] = i;
  }
}

void CornerGrid::query(cv::Point2d centre, double halfWidth, double halfHeight,
                       std::vector<int>& out) const {
  out.clear();
  if (sorted_.empty() || !std::isfinite(centre.x) || !std::isfinite(centre.y)) return;
  if (!(halfWidth >= 0) || !(halfHeight >= 0)) return;
  // Points are binned by their position's cell clamped into the grid (corners past the border
  // sit in the border cells), and clamping is monotonic: the clamped cells of the window's ends
  // bound those of every point inside it. Clamped in floating point (a far-off centre must not
  // overflow an int).
  const auto cellIndex = [&](double v, int last) {
    return static_cast<int>(std::clamp(std::floor(v / cell_), 0.0, static_cast<double>(last)));
  };
  const int x0 = cellIndex(centre.x - halfWidth, cols_ - 1);
  const int x1 = cellIndex(centre.x + halfWidth, cols_ - 1);
  const int y0 = cellIndex(centre.y - halfHeight, rows_ - 1);
  const int y1 = cellIndex(centre.y + halfHeight, rows_ - 1);
  for (int cy = y0; cy <= y1; ++cy) {
    // The cells x0..x1 of a row are adjacent in the compressed layout: one contiguous range.
    const int begin = cellStart_[static_cast<std::size_t>(cy * cols_ + x0)];
    const int end = cellStart_[static_cast<std::size_t>(cy * cols_ + x1 + 1)];
    for (int s = begin; s < end; ++s) {
      const cv::Point2f& p = sorted_[static_cast<std::size_t>(s)];
      if (std::abs(p.x - centre.x) <= halfWidth && std::abs(p.y - centre.y) <= halfHeight)
        out.push_back(sortedIndex_[static_cast<std::size_t>(s)]);
    }
  }
}

}  // namespace reftrack
