#pragma once
// MapPanel: building the reference map live - Capture reference, the captures as thumbnails
// (frame, pose source) with each pair's distance and view angle and a warning when a pair is too
// close or turned too far to triangulate, Build map with a progress bar, Add to map, Save map
// and the last result or error. Unprepared (no marker or board): the motion since the first
// capture (ready or not yet, and why) and the Baseline field. It only sets requests in
// MapState; LiveMapping carries them out.
#include <opencv2/core.hpp>

#include "app/viewer/ViewerState.hpp"

namespace reftrack::app {

void drawMapPanel(MapState& state, const cv::Rect2f& placement);

}  // namespace reftrack::app
