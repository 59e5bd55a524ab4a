#include "engine/relocalisation/RecoveryStage.hpp"

#include <gtest/gtest.h>

#include <set>

namespace reftrack {
namespace {

// Every stage has its own short name (the tables count stops by name, so two stages sharing one
// would be merged), none is empty or the fallback "unknown".
TEST(RecoveryStage, EveryStageHasItsOwnName) {
  const RecoveryStage all[] = {RecoveryStage::None,
                               RecoveryStage::NotSearched,
                               RecoveryStage::BlankFrame,
                               RecoveryStage::TooFewKeypoints,
                               RecoveryStage::TooFewMatches,
                               RecoveryStage::PnpInliers,
                               RecoveryStage::InlierShare,
                               RecoveryStage::InlierSpread,
                               RecoveryStage::StartNoPose,
                               RecoveryStage::SeededPass,
                               RecoveryStage::Correlation,
                               RecoveryStage::DistinctiveCorners,
                               RecoveryStage::KeypointSupport,
                               RecoveryStage::Verified};
  std::set<std::string> names;
  for (const RecoveryStage stage : all) {
    const std::string name = toString(stage);
    EXPECT_FALSE(name.empty());
    EXPECT_NE(name, "unknown");
    names.insert(name);
  }
  EXPECT_EQ(names.size(), std::size(all));
  EXPECT_EQ(toString(RecoveryStage::Verified), "verified");
  EXPECT_EQ(toString(RecoveryStage::PnpInliers), "PnP inliers");
  EXPECT_EQ(toString(static_cast<RecoveryStage>(99)), "unknown");
}

}  // namespace
}  // namespace reftrack
