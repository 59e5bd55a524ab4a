#pragma once
// DistinctiveCorners (issue 24 item 5): which corners of an image a correlation match can tell
// apart from their neighbours. A corner is repeated texture when another corner within `radius`
// pixels has a window correlating above `maxTwinScore` with its own (a chessboard's corners one
// square diagonal apart, tiles, a keyboard's keys): a start that matched only such corners may be
// off by a whole period and still be consistent, so a cold start is accepted only with enough
// support from distinctive ones.
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack {

// gray: CV_8UC1. 1 per distinctive corner, 0 per repeated one (a corner whose window leaves the
// image or is flat counts as repeated: it cannot vouch for a pose).
std::vector<char> distinctiveCorners(const cv::Mat& gray, const std::vector<cv::Point2f>& corners,
                                     int halfWindow, double radius, double maxTwinScore);

}  // namespace reftrack
