#pragma once
// MapPicture: one BGR picture of a reference map (drawn with OpenCV, no GL) — top: V_A and V_B
// side by side, every detected corner as a grey dot and every A<->B match as a line coloured by
// the depth of its 3D point; bottom: the 3D points (same colours) and the two reference cameras
// as frusta, seen from a virtual viewpoint behind and above the cameras.
#include <opencv2/core.hpp>

#include "engine/reference/ReferenceMap.hpp"

namespace reftrack::app {

// The picture is 2 * imageWidth wide and 2 * imageHeight high. Throws reftrack::Error on a map
// that fails ReferenceMap::check().
cv::Mat drawMapPicture(const ReferenceMap& map);

}  // namespace reftrack::app
