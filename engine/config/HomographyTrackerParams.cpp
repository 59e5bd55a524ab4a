#include "engine/config/HomographyTrackerParams.hpp"

#include "engine/config/ConfigValue.hpp"

namespace reftrack {

void HomographyTrackerParams::check() const {
  requireFiniteInRange("homography.guided_search_half_size_px", guidedSearchHalfSizePx, 0.5,
                       10000.0);
}

void HomographyTrackerParams::write(cv::FileStorage& fs) const {
  fs << "guided_search_half_size_px" << guidedSearchHalfSizePx << "frame_to_frame_prediction"
     << (frameToFramePrediction ? "true" : "false") << "reacquire_whole_image"
     << (reacquireWholeImage ? "true" : "false");
}

void HomographyTrackerParams::read(const cv::FileNode& node) {
  const std::string s = "homography";
  readConfigValue(node, s, "guided_search_half_size_px", guidedSearchHalfSizePx);
  readConfigValue(node, s, "frame_to_frame_prediction", frameToFramePrediction);
  readConfigValue(node, s, "reacquire_whole_image", reacquireWholeImage);
  check();
}

}  // namespace reftrack
