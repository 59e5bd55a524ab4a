// Relocaliser on real footage: the postcard clip, a map of its frames 0 and 100 (poses from the
// card corners, see PostcardCardPoses.hpp), every frame relocalised on its own (no tracking, no
// prior), each candidate compared with the card-corner pose of that frame and with the card's
// corners measured in it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "engine/relocalisation/PostcardCardPoses.hpp"
#include "engine/relocalisation/Relocaliser.hpp"

namespace reftrack {
namespace {

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::min<double>(v.size() - 1, p * (v.size() - 1) + 0.5))];
}

TEST(RelocaliserRealFootage, PostcardFramesRelocaliseAgainstAMapOfFrames0And100) {
  const std::optional<test::PostcardCardPoses> clip = test::PostcardCardPoses::load();
  if (!clip) GTEST_SKIP() << "../shared/data/planar-videos/video-postcard.mp4 not available";
  cv::setNumThreads(1);
  ASSERT_TRUE(clip->poses[0] && clip->poses[100]);
  MultiReferenceMap map;
  map.camera = clip->camera;
  for (const std::size_t k : {std::size_t{0}, std::size_t{100}}) {
    ReferenceView v;
    v.name = "frame_" + std::to_string(k) + ".png";
    v.T = *clip->poses[k];
    v.image = clip->frames[k];
    map.views.push_back(v);
  }
  const RelocalisationParams params;
  buildReferenceKeypoints(map, params);
  const Relocaliser relocaliser(map, params);

  std::vector<double> mm, deg, cornerPx, ms;
  int found = 0, measured = 0, wrong = 0;
  for (std::size_t k = 0; k < clip->frames.size(); ++k) {
    const RelocalisationAttempt a = relocaliser.locate(clip->frames[k]);
    ms.push_back(a.ms);
    if (!clip->poses[k]) continue;
    ++measured;
    if (!a.candidate) continue;
    ++found;
    const RigidPose& T = a.candidate->worldToCamera;
    mm.push_back(1000.0 * (T.cameraCentre() - clip->poses[k]->cameraCentre()).norm());
    deg.push_back(RigidPose::rotationDistance(T, *clip->poses[k]) * 180.0 / M_PI);
    double sum = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      const cv::Point3f& X = clip->card[i];
      const Eigen::Vector2d p = map.camera.project(T, Eigen::Vector3d(X.x, X.y, X.z));
      sum += std::hypot(p.x() - (*clip->corners[k])[i].x, p.y() - (*clip->corners[k])[i].y);
    }
    cornerPx.push_back(sum / 4.0);
    if (sum / 4.0 > 10.0) ++wrong;
  }
  const double rate = static_cast<double>(found) / std::max(measured, 1);
  std::printf(
      "postcard relocalisation (map: frames 0, 100; %d + %d 3D keypoints): %d of %d frames, "
      "centre error median %.1f mm p95 %.1f mm, rotation median %.2f deg, card corners median "
      "%.2f px p95 %.2f px max %.2f px, attempt median %.1f ms\n",
      map.views[0].keypoints.pointCount(), map.views[1].keypoints.pointCount(), found, measured,
      percentile(mm, 0.5), percentile(mm, 0.95), percentile(deg, 0.5), percentile(cornerPx, 0.5),
      percentile(cornerPx, 0.95), percentile(cornerPx, 1.0), percentile(ms, 0.5));
  RecordProperty("success_rate", std::to_string(rate));
  RecordProperty("card_corner_error_median_px", std::to_string(percentile(cornerPx, 0.5)));
  EXPECT_EQ(wrong, 0) << "a candidate more than 10 px off the card corners";
  EXPECT_GE(rate, 0.5);
  EXPECT_LT(percentile(cornerPx, 0.5), 3.0);
}

}  // namespace
}  // namespace reftrack
