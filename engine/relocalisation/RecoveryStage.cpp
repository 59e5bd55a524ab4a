#include "engine/relocalisation/RecoveryStage.hpp"

namespace reftrack {

std::string toString(RecoveryStage stage) {
  switch (stage) {
    case RecoveryStage::None:
      return "not tried";
    case RecoveryStage::NotSearched:
      return "not searched (budget spent)";
    case RecoveryStage::BlankFrame:
      return "blank frame";
    case RecoveryStage::TooFewKeypoints:
      return "too few keypoints";
    case RecoveryStage::TooFewMatches:
      return "too few keypoint matches";
    case RecoveryStage::PnpInliers:
      return "PnP inliers";
    case RecoveryStage::InlierShare:
      return "inlier share";
    case RecoveryStage::InlierSpread:
      return "inlier spread";
    case RecoveryStage::StartNoPose:
      return "no start pose";
    case RecoveryStage::SeededPass:
      return "seeded pass";
    case RecoveryStage::Correlation:
      return "correlation check";
    case RecoveryStage::DistinctiveCorners:
      return "distinctive corners";
    case RecoveryStage::KeypointSupport:
      return "keypoint support";
    case RecoveryStage::Verified:
      return "verified";
  }
  return "unknown";
}

}  // namespace reftrack
