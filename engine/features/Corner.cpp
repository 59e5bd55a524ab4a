#include "engine/features/Corner.hpp"

namespace reftrack {

std::vector<cv::Point2f> positionsOf(const std::vector<Corner>& corners) {
  std::vector<cv::Point2f> out;
  out.reserve(corners.size());
  for (const Corner& c : corners) out.push_back(c.position);
  return out;
}

}  // namespace reftrack
