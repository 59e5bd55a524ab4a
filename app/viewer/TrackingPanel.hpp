#pragma once
// TrackingPanel: the tracker's parameters (TrackerParams) — mode, pose estimator, alpha, process
// noise Q (or a fitted motion-model file), RANSAC iterations and early exit, correlation window
// and threshold, search window, corner count — plus saving/loading them as the YAML file every
// command-line tool accepts. Any edit sets state.trackerParamsChanged; the loop applies it.
#include <opencv2/core.hpp>

#include "app/viewer/ViewerState.hpp"

namespace reftrack::app {

void drawTrackingPanel(ViewerState& state, const cv::Rect2f& placement);

}  // namespace reftrack::app
