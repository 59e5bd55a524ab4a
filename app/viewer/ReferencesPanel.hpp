#pragma once
// ReferencesPanel: 6-DOF tracking over a multi-reference map — a thumbnail of every reference
// with the two in use highlighted, and the relocalisation attempts, successes and their last and
// median time. ReferencesState holds what it shows; addFrame() folds in one tracked frame.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "app/viewer/FrameTracker.hpp"

namespace reftrack::app {

struct ReferencesState {
  bool active = false;  // the tracker runs over a reference map (the panel is shown)
  std::vector<std::string> names;
  std::vector<unsigned int> thumbnails;  // GL texture ids, one per reference (0: name only)
  cv::Size thumbnailSize{0, 0};
  int referenceA = -1, referenceB = -1;  // the pair in use on the last frame
  int attempts = 0, successes = 0;       // relocalisation, since the start
  std::vector<double> attemptMs;         // recent attempts' times (the last 500-1000)
  std::string lastMessage;               // the last attempt's result
  void addFrame(const ReferencesFrame& frame);
  double lastMs() const;    // NaN before the first attempt
  double medianMs() const;  // NaN before the first attempt
};

void drawReferencesPanel(const ReferencesState& state, const cv::Rect2f& placement);

}  // namespace reftrack::app
