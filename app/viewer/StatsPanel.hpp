#pragma once
// StatsPanel: loop rate, per-stage milliseconds and match/inlier counts of the last frame, and the
// pose components (translation in metres, rotation vector in radians) plotted over recent frames.
#include <opencv2/core.hpp>

#include "app/viewer/StatsHistory.hpp"

namespace reftrack::app {

void drawStatsPanel(const StatsHistory& stats, const cv::Rect2f& placement);

}  // namespace reftrack::app
