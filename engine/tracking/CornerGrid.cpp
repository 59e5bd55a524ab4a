#include "engine/tracking/CornerGrid.hpp"

#include <algorithm>
#include <cmath>

#include "engine/core/Error.hpp"

namespace reftrack {

CornerGrid::CornerGrid(const std::vector<cv::Point2f>& points, cv::Size imageSize, int cellSize)
    : points_(points), cell_(std::max(1, cellSize)) {
  if (imageSize.width <= 0 || imageSize.height <= 0) throw Error("CornerGrid: empty image size");
  cols_ = (imageSize.width + cell_ - 1) / cell_;
  rows_ = (imageSize.height + cell_ - 1) / cell_;
  cells_.assign(static_cast<std::size_t>(cols_ * rows_), {});
  for (int i = 0; i < static_cast<int>(points_.size()); ++i) {
    const int cx = std::clamp(static_cast<int>(points_[i].x) / cell_, 0, cols_ - 1);
    const int cy = std::clamp(static_cast<int>(points_[i].y) / cell_, 0, rows_ - 1);
    cells_[static_cast<std::size_t>(cy * cols_ + cx)].push_back(i);
  }
}

void CornerGrid::query(cv::Point2d centre, double halfWidth, double halfHeight,
                       std::vector<int>& out) const {
  out.clear();
  if (points_.empty() || !std::isfinite(centre.x) || !std::isfinite(centre.y)) return;
  const int x0 = std::max(0, static_cast<int>(std::floor((centre.x - halfWidth) / cell_)));
  const int x1 = std::min(cols_ - 1, static_cast<int>(std::floor((centre.x + halfWidth) / cell_)));
  const int y0 = std::max(0, static_cast<int>(std::floor((centre.y - halfHeight) / cell_)));
  const int y1 = std::min(rows_ - 1, static_cast<int>(std::floor((centre.y + halfHeight) / cell_)));
  for (int cy = y0; cy <= y1; ++cy)
    for (int cx = x0; cx <= x1; ++cx)
      for (int i : cells_[static_cast<std::size_t>(cy * cols_ + cx)]) {
        const cv::Point2f& p = points_[static_cast<std::size_t>(i)];
        if (std::abs(p.x - centre.x) <= halfWidth && std::abs(p.y - centre.y) <= halfHeight)
          out.push_back(i);
      }
}

}  // namespace reftrack
