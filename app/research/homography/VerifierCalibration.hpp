#pragma once
// How reliable the registration check is on real pairs (issue 26): RegistrationVerifier is given
// each pair's true homography and copies of it moved by a known amount at the frame's corners
// (each corner displaced by `d` pixels in a random direction); a reliable check passes the truth
// and refuses every homography far off. The true homographies of real pairs are themselves only
// good to about a pixel, and blurred or relit frames lower the correlation: both show here.
#include <cstdint>
#include <string>
#include <vector>

#include "app/research/homography/HomographyPair.hpp"
#include "engine/homography/RegistrationVerifier.hpp"

namespace reftrack::app {

struct VerifierOutcome {
  double offsetPx = 0.0;  // corner displacement of the homography checked (0: the truth)
  bool passed = false;
  int measurable = 0, confirmed = 0;
  double spread = 0.0;
  double measuredOffsetPx = 0.0;  // the check's estimate of how far off H is (RegistrationCheck)
  std::string failure;            // why it did not pass
};

struct VerifierPairResult {
  std::vector<VerifierOutcome> outcomes;  // per offset, `trials` each (the truth once)
};

// offsets: the corner displacements tried (pixels), each `trials` times with random directions.
std::vector<VerifierPairResult> runVerifierCalibration(const std::vector<HomographyPair>& pairs,
                                                       const std::vector<double>& offsets,
                                                       int trials, std::uint64_t seed,
                                                       const RegistrationCheckParams& params = {});

// H moved so that the frame's four corners (of `size`) land `offsets[i]` away from where H puts
// them: the homography taking those corners to the moved ones, composed with H.
cv::Matx33d displacedHomography(const cv::Matx33d& H, cv::Size size,
                                const std::vector<cv::Point2d>& offsets);

}  // namespace reftrack::app
