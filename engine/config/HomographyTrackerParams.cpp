#include "engine/config/HomographyTrackerParams.hpp"

#include "engine/config/ConfigValue.hpp"

namespace reftrack {

void HomographyTrackerParams::check() const {
  requireFiniteInRange("homography.guided_search_half_size_px", guidedSearchHalfSizePx, 0.5,
                       10000.0);
  requireFiniteInRange("homography.reacquire_corner_factor", reacquireCornerFactor, 1.0, 16.0);
  requireFiniteInRange("homography.reacquire_corner_quality", reacquireCornerQuality, 1e-6, 1.0);
  requireFiniteInRange("homography.reacquire_min_distance_px", reacquireMinDistancePx, 1.0, 1000.0);
  requireFiniteInRange("homography.frame_corner_factor", frameCornerFactor, 1.0, 16.0);
}

void HomographyTrackerParams::write(cv::FileStorage& fs) const {
  fs << "guided_search_half_size_px" << guidedSearchHalfSizePx << "frame_to_frame_prediction"
     << (frameToFramePrediction ? "true" : "false") << "reacquire_whole_image"
     << (reacquireWholeImage ? "true" : "false") << "reacquire_corner_factor"
     << reacquireCornerFactor << "reacquire_corner_quality" << reacquireCornerQuality
     << "reacquire_min_distance_px" << reacquireMinDistancePx << "frame_corner_factor"
     << frameCornerFactor << "rotation_model" << (rotationModel ? "true" : "false");
}

void HomographyTrackerParams::read(const cv::FileNode& node) {
  const std::string s = "homography";
  readConfigValue(node, s, "guided_search_half_size_px", guidedSearchHalfSizePx);
  readConfigValue(node, s, "frame_to_frame_prediction", frameToFramePrediction);
  readConfigValue(node, s, "reacquire_whole_image", reacquireWholeImage);
  readConfigValue(node, s, "reacquire_corner_factor", reacquireCornerFactor);
  readConfigValue(node, s, "reacquire_corner_quality", reacquireCornerQuality);
  readConfigValue(node, s, "reacquire_min_distance_px", reacquireMinDistancePx);
  readConfigValue(node, s, "frame_corner_factor", frameCornerFactor);
  readConfigValue(node, s, "rotation_model", rotationModel);
  check();
}

}  // namespace reftrack
