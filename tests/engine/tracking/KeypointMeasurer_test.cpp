#include "engine/tracking/KeypointMeasurer.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "PlaneWorld.hpp"

namespace reftrack {
namespace {

using test::applyH;
using test::PlaneWorld;

// Keypoints: the reference A's corners (well-textured spots) with their exact 3D points, and B's
// the same way through the plane.
std::vector<MeasurableKeypoint> keypointsOf(const PlaneWorld& world, const ReferenceMap& map) {
  std::vector<MeasurableKeypoint> out;
  for (const ReferenceCorner& c : map.cornersA)
    out.push_back({world.backProject(c.pixel), c.pixel, 0});
  const cv::Matx33d BtoA = world.homography(world.T_AB).inv();
  for (const ReferenceCorner& c : map.cornersB) {
    const cv::Point2d a = applyH(BtoA, c.pixel);
    out.push_back({world.backProject(cv::Point2f(static_cast<float>(a.x), static_cast<float>(a.y))),
                   c.pixel, 1});
  }
  return out;
}

// The frame seen from a pose between and beyond the references; the measurer is given a pose a
// pixel or so off (as the robust linear pose may be): the aligned pixels must land where the
// points truly are, not where the given pose puts them.
TEST(KeypointMeasurer, AlignsWhereThePointsTrulyAreFromAPoseAPixelOff) {
  const PlaneWorld world;
  const ReferenceMap map = world.map();
  cv::Mat grayA, grayB;
  map.imageA.copyTo(grayA);
  map.imageB.copyTo(grayB);
  const KeypointMeasurer measurer(map.camera, keypointsOf(world, map), grayA, grayB, {});
  const RigidPose T_Ak =
      RigidPose::fromVector6((Vector6d() << -0.08, 0.03, 0.05, 0.02, 0.06, -0.03).finished());
  const cv::Mat frame = world.render(T_Ak, 7);
  // About 1-2 px off in the image (1 mrad ~ 0.5 px at f = 520, 2 mm at ~1 m ~ 1 px).
  const RigidPose off =
      RigidPose::fromVector6((Vector6d() << 0.002, -0.001, 0.0, 0.002, -0.001, 0.001).finished()) *
      T_Ak;
  const std::vector<KeypointMeasurement> found = measurer.measure(frame, off, 0);
  ASSERT_GT(found.size(), 150u);
  double sumAligned = 0.0, sumPredicted = 0.0;
  std::vector<double> aligned;
  for (const KeypointMeasurement& m : found) {
    const Eigen::Vector3d X = T_Ak * measurer.points()[static_cast<std::size_t>(m.point)].pointA;
    const Eigen::Vector2d truth = map.camera.project(X);
    const cv::Point2d t(truth.x(), truth.y());
    aligned.push_back(cv::norm(cv::Point2d(m.pixel) - t));
    sumAligned += aligned.back();
    sumPredicted += cv::norm(cv::Point2d(m.predicted) - t);
  }
  const double meanAligned = sumAligned / static_cast<double>(found.size());
  const double meanPredicted = sumPredicted / static_cast<double>(found.size());
  std::nth_element(aligned.begin(), aligned.begin() + static_cast<long>(aligned.size() * 9 / 10),
                   aligned.end());
  const double p90 = aligned[aligned.size() * 9 / 10];
  // Measured: 232 points, predicted 1.66 px off on average, aligned 0.035 px (exact plane, noise
  // SD 2 grey levels, 15x15 windows): the tolerances leave about 3x room.
  EXPECT_GT(meanPredicted, 0.8);
  EXPECT_LT(meanAligned, 0.1);
  EXPECT_LT(p90, 0.2);
  RecordProperty("measured", std::to_string(found.size()));
  RecordProperty("mean_predicted_px", std::to_string(meanPredicted));
  RecordProperty("mean_aligned_px", std::to_string(meanAligned));
  RecordProperty("p90_aligned_px", std::to_string(p90));
}

TEST(KeypointMeasurer, TriesAtMostTheCapAndSkipsPointsOutsideTheFrame) {
  const PlaneWorld world;
  const ReferenceMap map = world.map();
  cv::Mat grayA, grayB;
  map.imageA.copyTo(grayA);
  map.imageB.copyTo(grayB);
  const KeypointMeasurer measurer(map.camera, keypointsOf(world, map), grayA, grayB, {});
  const RigidPose T_Ak = RigidPose();
  const cv::Mat frame = world.render(T_Ak, 3);
  EXPECT_LE(measurer.measure(frame, T_Ak, 20).size(), 20u);
  // Turned 90 degrees away: nothing projects into the frame.
  const RigidPose away = RigidPose::fromVector6((Vector6d() << 0, 0, 0, 0, 1.5708, 0).finished());
  EXPECT_TRUE(measurer.measure(frame, away, 0).empty());
}

}  // namespace
}  // namespace reftrack
