#pragma once
// CornerGrid: a bucket grid over corner positions for fast "which corners lie inside this
// rectangle" queries (the (2dx+1) x (2dy+1) candidate windows of wide-baseline matching).
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack {

class CornerGrid {
 public:
  CornerGrid() = default;
  CornerGrid(const std::vector<cv::Point2f>& points, cv::Size imageSize, int cellSize);

  // Indices of points with |x - centre.x| <= halfWidth and |y - centre.y| <= halfHeight.
  void query(cv::Point2d centre, double halfWidth, double halfHeight, std::vector<int>& out) const;
  bool empty() const { return points_.empty(); }

 private:
  std::vector<cv::Point2f> points_;
  std::vector<std::vector<int>> cells_;
  int cols_ = 0, rows_ = 0, cell_ = 1;
};

}  // namespace reftrack
