#pragma once
// StatsPanel: loop rate, per-stage milliseconds and match/inlier counts of the last frame, and
// plotted over recent frames the pose components (translation in metres, rotation vector in
// radians), the inliers, the overlay error predicted from the pose covariance ("pred", pixels)
// and, when the viewer has ground truth (StatsHistory::groundTruthLoaded), the true one ("true")
// on the same scale.
#include <opencv2/core.hpp>

#include "app/viewer/StatsHistory.hpp"

namespace reftrack::app {

void drawStatsPanel(const StatsHistory& stats, const cv::Rect2f& placement);

}  // namespace reftrack::app
