#pragma once
// MapPicture: one BGR picture of a reference map (drawn with OpenCV, no GL) — top: every
// reference image (two side by side at full size, more in a grid scaled to the same width), each
// detected corner as a grey dot and each corner of a map point in the colour of the point's depth
// (two references: every match also as a line); bottom: the 3D points (same colours) and every
// reference camera as a frustum with its index, seen from behind and above the cameras.
#include <opencv2/core.hpp>

#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack::app {

// The picture is 2 * imageWidth wide and imageHeight + the tile rows high (two references:
// 2 * imageHeight, the top row V_A | V_B). Throws reftrack::Error on a map that fails its check().
cv::Mat drawMapPicture(const MultiReferenceMap& map);
cv::Mat drawMapPicture(const ReferenceMap& map);

}  // namespace reftrack::app
