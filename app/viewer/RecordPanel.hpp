#pragma once
// RecordPanel: start/stop recording the composited output (MP4 + TUM trajectory beside it) to a
// chosen path.
#include <opencv2/core.hpp>

#include "app/viewer/ViewerState.hpp"

namespace reftrack::app {

void drawRecordPanel(RecordState& state, const cv::Rect2f& placement);

}  // namespace reftrack::app
