#pragma once
// Paper Fig. 11: one reference corner of V_A followed over a sequence that moves away from the
// reference, scored at its true position in every frame with the standard NCC (Eq. 17, square
// windows) and with the warped correlation (Eq. 19, the window mapped by the exact desk-plane
// homography between the frame and V_A). The standard score falls as the viewpoint changes; the
// warped one stays high.
#include <vector>

#include "app/research/sixdof/SimulatedSequence.hpp"

namespace reftrack::app {

struct CorrelationDecayResult {
  int referenceCorner = -1;  // index into the map's cornersA
  Eigen::Vector3d worldPoint;
  std::vector<int> frames;
  std::vector<double> standardScore, warpedScore;
  std::vector<double> viewAngleDeg;  // angle between the frame's and V_A's viewing rays
};

// Picks the strongest-contrast map point on the desk plane (world z = 0) that stays inside every
// frame, and scores it in each frame. Throws reftrack::Error when no such point exists.
CorrelationDecayResult runCorrelationDecay(const SimulatedSequence& s, int halfWindow);

}  // namespace reftrack::app
