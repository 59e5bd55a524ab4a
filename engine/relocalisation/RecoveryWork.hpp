#pragma once
// RecoveryWork: the work a lost tracker's recovery did (re-seeds, starts near a reference,
// relocaliser searches), counted, and the milliseconds it is modelled to cost. On recorded input
// the relocalisation budget (RelocalisationBudget) is charged this modelled cost instead of a
// measured time, so the same frames and parameters give the same decisions on any machine and
// under any load. The coefficients (RecoveryCostModel) are CPU milliseconds of one core of the
// development machine class, fitted by `reftrack bench-recovery-cost`
// (app/research/README.md, "The recovery's cost model").
#include <string>

namespace reftrack {

// Keypoint work of the relocaliser (Relocaliser::locate, ratioTestSupport).
struct KeypointWork {
  double detectedMegapixels = 0.0;   // pixels of the images keypoints were detected on (10^6)
  double comparisonsMillions = 0.0;  // descriptor distances computed (frame x reference, 10^6)
  int poseSearches = 0;              // PnP-RANSAC runs (each with its refinements)
  KeypointWork& operator+=(const KeypointWork& o);
};

// The tracker passes and keypoint work of a recovery. Pass counts are weighted by the frame's
// size in megapixels (a pass's corners and matches scale with the image area).
struct RecoveryWork {
  double startPassMegapixels = 0.0;     // passes from no pose (the start near a reference)
  double seededPassMegapixels = 0.0;    // passes from a seed's wide search (re-seed, a start's
                                        // confirmation, a relocalisation candidate's verification)
  double repeatedPassMegapixels = 0.0;  // the pair tracker's pass again around its own pose
  KeypointWork keypoints;
  RecoveryWork& operator+=(const RecoveryWork& o);
  RecoveryWork operator-(const RecoveryWork& o) const;
};

// Milliseconds per unit of work. `defaults(kind)`: the coefficients measured for a keypoint
// detector (sift, orb, akaze; the tracker passes are the same for all).
struct RecoveryCostModel {
  double msPerStartPassMegapixel = 0.0;
  double msPerSeededPassMegapixel = 0.0;
  double msPerRepeatedPassMegapixel = 0.0;
  double msPerDetectedMegapixel = 0.0;
  double msPerMillionComparisons = 0.0;
  double msPerPoseSearch = 0.0;

  // Throws reftrack::Error for an unknown kind.
  static RecoveryCostModel defaults(const std::string& keypointKind);
  double ms(const RecoveryWork& work) const;  // the modelled cost
};

}  // namespace reftrack
