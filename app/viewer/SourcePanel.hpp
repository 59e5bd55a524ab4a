#pragma once
// SourcePanel: the frame source — play/pause, single step, seek slider, playback speed, loop.
#include <opencv2/core.hpp>

#include "app/viewer/ViewerState.hpp"

namespace reftrack::app {

void drawSourcePanel(SourceState& state, const cv::Rect2f& placement);

}  // namespace reftrack::app
