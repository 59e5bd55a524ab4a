#pragma once
// Registration of image pairs with known homographies: for every sequence folder of a data
// directory laid out like the Oxford affine benchmark (img1.png..img6.png, H1to{N}p.xml), the
// real pairs img1 -> imgN, plus views synthesised from img1 with exact homographies — a plane
// tilted out of the image by 20-60 degrees and zoom 0.5-3.5 with in-plane rotation — and the
// hard sets of issue 26 (HardHomographyPairs.hpp: strong viewpoint, zoom to 4x, repeated brick
// and tile texture, frames of another size than the reference). The tracker (cold: reset before
// each pair) and plain OpenCV baselines (OpenCvFeatureBaseline) register the very same pairs,
// each timed in thread CPU. Error: mean registration error at the frame's four corners
// (frameCornerError).
#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "app/research/homography/HomographyPair.hpp"
#include "app/research/homography/SyntheticViews.hpp"
#include "engine/config/TrackerParams.hpp"

namespace reftrack::app {

// All pairs of every sequence folder under dataDir (sorted by name): the real pairs (sequence:
// the folder's name; frames of any size), then its synthesised views (sequence "<name>-views").
// Throws reftrack::Error when there is none.
std::vector<HomographyPair> buildHomographyPairs(const std::filesystem::path& dataDir,
                                                 double noiseSigma, std::uint64_t seed);

struct PairOutcome {
  bool found = false;
  double cornerErrorPx = 0.0;  // NaN when not found
  double milliseconds = 0.0;   // thread CPU time of the registration
  std::string failure;         // reftrack: why it was not registered
};

struct PairsMethod {
  std::string name;
  std::vector<PairOutcome> outcomes;  // one per pair, in order
};

struct PairsOptions {
  std::filesystem::path dataDir;
  double noiseSigma = 2.0;
  std::uint64_t seed = 1;
  bool broadViews = true;  // the 18 views synthesised from each sequence's img1 ("<seq>-views")
  bool hardSets = true;    // the hard sets (HardHomographyPairs.hpp)
  std::vector<std::string> onlySets;  // when not empty: only the pairs of these sets
  int wallSupersample = 4;            // rays per pixel (squared) of the simulated walls (1..8; see
                                      // buildHardHomographyPairs)
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
