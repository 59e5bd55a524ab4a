#pragma once
// Registration of real image pairs with known homographies: for every sequence folder of a data
// directory laid out like the Oxford affine benchmark (img1.png..img6.png, H1to{N}p.xml), the
// real pairs img1 -> imgN, plus views synthesised from img1 with exact homographies — a plane
// tilted out of the image by 20-60 degrees (viewpoint, like graf/wall) and zoom 0.5-3.5 with
// in-plane rotation (like boat/bark). The tracker (cold: reset before each pair) and plain
// OpenCV baselines (OpenCvFeatureBaseline) register the very same pairs. Error: mean
// registration error at the frame's four corners (frameCornerError).
#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "engine/config/TrackerParams.hpp"

namespace reftrack::app {

struct HomographyPair {
  std::string sequence;
  std::string kind;  // "photometric" (real imgN), "viewpoint" or "zoom-rotation" (synthesised)
  std::string label;
  cv::Mat reference, frame;  // grey, same size
  cv::Matx33d truth;         // reference -> frame
};

// The homography of a plane seen head-on filling `size` (focal length = width) when the camera
// is tilted by tiltDeg about the in-plane axis at azimuthDeg, rolled by rollDeg about its optical
// axis and moved to 1/scale of the distance, looking at the image centre.
cv::Matx33d syntheticViewHomography(cv::Size size, double tiltDeg, double azimuthDeg, double scale,
                                    double rollDeg);

// `image` seen through H (reference -> frame) at the same size: warped at twice the resolution
// and area-averaged down (no aliasing when zooming out), plus Gaussian noise of SD noiseSigma.
cv::Mat synthesiseView(const cv::Mat& image, const cv::Matx33d& H, double noiseSigma,
                       std::uint64_t seed);

// All pairs of every sequence folder under dataDir (sorted by name). Throws reftrack::Error when
// there is none.
std::vector<HomographyPair> buildHomographyPairs(const std::filesystem::path& dataDir,
                                                 double noiseSigma, std::uint64_t seed);

struct PairOutcome {
  bool found = false;
  double cornerErrorPx = 0.0;  // NaN when not found
  double milliseconds = 0.0;
};

struct PairsMethod {
  std::string name;
  std::vector<PairOutcome> outcomes;  // one per pair, in order
};

struct PairsOptions {
  std::filesystem::path dataDir;
  double noiseSigma = 2.0;
  std::uint64_t seed = 1;
  TrackerParams params;
  void check() const;  // throws reftrack::Error naming the bad field
};

struct PairsResult {
  std::vector<HomographyPair> pairs;
  // "reftrack" (params as given), "reftrack-ncc" (the keypoint layer off: unguided correlation
  // only), then the OpenCV baselines "sift", "akaze", "orb".
  std::vector<PairsMethod> methods;
};

PairsResult runPairsExperiment(const PairsOptions& options);

}  // namespace reftrack::app
