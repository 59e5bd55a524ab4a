#pragma once
// HomographyPair: one registration problem of the pairs experiments — a reference image, a frame
// of the same planar scene (any sizes: the frame may come from another camera) and the exact
// reference -> frame homography.
#include <opencv2/core.hpp>
#include <string>

namespace reftrack::app {

struct HomographyPair {
  std::string sequence;  // the pair set (pairs of one set share their reference)
  std::string kind;      // real pairs: the data folder holding the set (e.g. "oxford-viewpoint");
                         // synthesised: "viewpoint" or "zoom-rotation"
  std::string label;
  cv::Mat reference, frame;  // grey
  cv::Matx33d truth;         // reference -> frame
  bool real = false;         // two photographs and the data set's homography (not synthesised)
};

}  // namespace reftrack::app
