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

  // Indices of points with |x - centre.x| <= halfWidth and |y - centre.y| <= halfHeight, cell by
  // cell (row-major) and within a cell in index order.
  void query(cv::Point2d centre, double halfWidth, double halfHeight, std::vector<int>& out) const;
  bool empty() const { return sorted_.empty(); }

 private:
  // Compressed rows: the points of cell i are entries cellStart_[i] .. cellStart_[i + 1] - 1 of
  // sorted_ (their positions) and sortedIndex_ (their indices), so a query reads contiguous
  // memory instead of one heap block per cell (a tracked 1280x720 frame makes ~700 queries).
  std::vector<int> cellStart_;
  std::vector<cv::Point2f> sorted_;
  std::vector<int> sortedIndex_;
  int cols_ = 0, rows_ = 0, cell_ = 1;
};

}  // namespace reftrack
