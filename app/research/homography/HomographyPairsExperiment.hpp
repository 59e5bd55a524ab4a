#pragma once
// Registration of image pairs with known homographies: every sequence folder found under a data
// directory laid out like the Oxford affine benchmark (img1 + img2..img6 as .png/.ppm/.pgm/.jpg,
// H1toNp or H1toNp.xml, x_N ~ H1toNp x_1), its real pairs img1 -> imgN. On request
// (syntheticViews / hardSets) also views synthesised from img1 with exact homographies and the
// simulated hard sets (HardHomographyPairs.hpp) — kept for tests, no longer evidence: real
// photographs do not behave like them. The tracker (cold: reset before each pair) and plain
// OpenCV baselines (OpenCvFeatureBaseline) register the very same pairs, each timed (wall clock
// and thread CPU, one thread). Errors: at the reference's four corners (referenceCornerError, the
// Oxford convention) and over the overlap (meanTransferDeviation on a reference grid).
#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "app/research/homography/HomographyPair.hpp"
#include "app/research/homography/SyntheticViews.hpp"
#include "app/research/homography/TruthRefinement.hpp"
#include "engine/config/TrackerParams.hpp"

namespace reftrack::app {

// The sequence folders under dataDir (itself when it holds img1, else its sub-folders up to three
// levels down that do), sorted by path. Throws reftrack::Error when dataDir is not a folder.
std::vector<std::filesystem::path> findPairSequences(const std::filesystem::path& dataDir);

// All real pairs of every sequence folder under dataDir (sequence: the folder's name, kind: its
// parent folder's name; frames of any size), each followed, when syntheticViews, by 18 views
// synthesised from its img1 (sequence "<name>-views"). Throws reftrack::Error when there is no
// sequence, or an image or homography file cannot be read.
std::vector<HomographyPair> buildHomographyPairs(const std::filesystem::path& dataDir,
                                                 double noiseSigma, std::uint64_t seed,
                                                 bool syntheticViews = false);

struct PairOutcome {
  bool found = false;
  double cornerErrorPx = 0.0;   // at the reference's corners; NaN when not found
  double overlapErrorPx = 0.0;  // over the reference points the frame sees; NaN when not found
  double milliseconds = 0.0;    // thread CPU time of the registration
  double wallMs = 0.0;          // wall-clock time of the registration
  std::string failure;          // reftrack: why it was not registered
  std::string check;            // reftrack: what its registration check compared and found
  std::vector<std::pair<std::string, double>> stageMs;  // reftrack: per stage (wall clock)
};

struct PairsMethod {
  std::string name;
  std::vector<PairOutcome> outcomes;  // one per pair, in order
};

struct PairsOptions {
  std::filesystem::path dataDir;
  double noiseSigma = 2.0;
  std::uint64_t seed = 1;
  bool broadViews = false;  // the 18 views synthesised from each sequence's img1 ("<seq>-views")
  bool hardSets = false;    // the simulated hard sets (HardHomographyPairs.hpp)
  std::vector<std::string> onlySets;  // when not empty: only the pairs of these sets
  int wallSupersample = 4;            // rays per pixel (squared) of the simulated walls (1..8; see
                                      // buildHardHomographyPairs)
  bool peers = true;                  // also the OpenCV peers (SIFT, AKAZE, ORB)
  // The given homographies of the real pairs replaced by their ECC refinement
  // (refineTruthByEcc) where it converges.
  bool refineTruth = false;
  // Each real pair registered at these scales of both images (resampled: area below 1, cubic
  // above; the homography carried exactly), as set "<name>@<scale>" unless the scale is 1.
  std::vector<double> scales = {1.0};
  TrackerParams params;
  void check() const;  // throws reftrack::Error naming the bad field
};

struct PairsResult {
  std::vector<HomographyPair> pairs;
  // With refineTruth: per pair, the ECC refinement of its given homography (at scale 1; empty
  // entries for synthesised pairs).
  std::vector<RefinedTruth> truthChecks;
  // "reftrack" (params as given), "reftrack-ncc" (the keypoint layer off: unguided correlation
  // only), then, with peers, the OpenCV baselines "sift", "akaze", "orb".
  std::vector<PairsMethod> methods;
};

PairsResult runPairsExperiment(const PairsOptions& options);

}  // namespace reftrack::app
