#include "engine/relocalisation/RecoveryWork.hpp"

#include "engine/core/Error.hpp"

namespace reftrack {

KeypointWork& KeypointWork::operator+=(const KeypointWork& o) {
  detectedMegapixels += o.detectedMegapixels;
  comparisonsMillions += o.comparisonsMillions;
  poseSearches += o.poseSearches;
  return *this;
}

RecoveryWork& RecoveryWork::operator+=(const RecoveryWork& o) {
  startPassMegapixels += o.startPassMegapixels;
  seededPassMegapixels += o.seededPassMegapixels;
  repeatedPassMegapixels += o.repeatedPassMegapixels;
  keypoints += o.keypoints;
  return *this;
}

RecoveryWork RecoveryWork::operator-(const RecoveryWork& o) const {
  RecoveryWork d;
  d.startPassMegapixels = startPassMegapixels - o.startPassMegapixels;
  d.seededPassMegapixels = seededPassMegapixels - o.seededPassMegapixels;
  d.repeatedPassMegapixels = repeatedPassMegapixels - o.repeatedPassMegapixels;
  d.keypoints.detectedMegapixels = keypoints.detectedMegapixels - o.keypoints.detectedMegapixels;
  d.keypoints.comparisonsMillions = keypoints.comparisonsMillions - o.keypoints.comparisonsMillions;
  d.keypoints.poseSearches = keypoints.poseSearches - o.keypoints.poseSearches;
  return d;
}

RecoveryCostModel RecoveryCostModel::defaults(const std::string& keypointKind) {
  // Fitted by scripts/calibrate-recovery-cost.sh (`reftrack bench-recovery-cost`: one thread,
  // each recovery's least CPU time of its plays, relative least squares; app/research/README.md,
  // "The recovery's cost model"). Columns: start, seeded, repeated pass (per megapixel of frame),
  // detection (per megapixel detected), comparisons (per million), PnP-RANSAC run. SIFT: the desk
  // (752x480, references 0/40) and shelf (references 0/60) clips pooled, 806 recoveries; ORB and
  // AKAZE: the desk's first 200 frames.
  struct Row {
    const char* kind;
    double c[6];
  };
  static constexpr Row kRows[] = {
      {"sift", {9.33, 11.92, 2.33, 153.93, 6.11, 4.63}},
      {"orb", {7.95, 8.17, 6.09, 0.0, 3.46, 11.40}},
      {"akaze", {7.93, 9.04, 5.47, 140.57, 17.17, 7.57}},
  };
  for (const Row& row : kRows) {
    if (keypointKind != row.kind) continue;
    RecoveryCostModel m;
    m.msPerStartPassMegapixel = row.c[0];
    m.msPerSeededPassMegapixel = row.c[1];
    m.msPerRepeatedPassMegapixel = row.c[2];
    m.msPerDetectedMegapixel = row.c[3];
    m.msPerMillionComparisons = row.c[4];
    m.msPerPoseSearch = row.c[5];
    return m;
  }
  throw Error("recovery cost model: unknown keypoint kind '" + keypointKind + "'");
}

double RecoveryCostModel::ms(const RecoveryWork& w) const {
  return msPerStartPassMegapixel * w.startPassMegapixels +
         msPerSeededPassMegapixel * w.seededPassMegapixels +
         msPerRepeatedPassMegapixel * w.repeatedPassMegapixels +
         msPerDetectedMegapixel * w.keypoints.detectedMegapixels +
         msPerMillionComparisons * w.keypoints.comparisonsMillions +
         msPerPoseSearch * w.keypoints.poseSearches;
}

}  // namespace reftrack
