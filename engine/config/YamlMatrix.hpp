#pragma once
// YamlMatrix: an OpenCV matrix in a YAML file, as cv::FileStorage writes it —
//   K: !!opencv-matrix {rows: 3, cols: 3, dt: d, data: [500., 0., 319.5, ...]}
// (the tag may be left out by hand). The header is checked against the data before anything is
// allocated, so "rows: 2000000000" in a file of a few bytes costs nothing.
#include <opencv2/core.hpp>

#include "engine/config/YamlNode.hpp"

namespace reftrack {

// Throws reftrack::Error "line N: <name> is not a valid matrix: <why>" unless `node` is a map of
// rows, cols (counts), dt (an element type: u c w s i f d h, optionally after a channel count,
// "3f") and data (rows x cols x channels numbers; integers within the type's range for u c w s
// i; data may be left out when that is 0).
cv::Mat readYamlMatrix(const YamlNode& node);

}  // namespace reftrack
