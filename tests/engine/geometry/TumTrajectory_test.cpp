#include "engine/geometry/TumTrajectory.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

TEST(TumTrajectory, RoundTripsWorldToCameraPoses) {
  const auto dir = test::freshTempDir("Tum_RoundTrip");
  TumTrajectory traj;
  for (int i = 0; i < 20; ++i) {
    Vector6d x;
    x << 0.01 * i, -0.3, 1.0 + 0.02 * i, 0.1, -0.05 * i, 0.02;
    traj.poses.push_back({i / 30.0, RigidPose::fromVector6(x)});
  }
  traj.save(dir / "t.txt");
  const TumTrajectory back = TumTrajectory::load(dir / "t.txt");
  ASSERT_EQ(back.poses.size(), traj.poses.size());
  for (size_t i = 0; i < traj.poses.size(); ++i) {
    EXPECT_NEAR(back.poses[i].timestamp, traj.poses[i].timestamp, 1e-6);
    EXPECT_LT(
        (back.poses[i].worldToCamera.matrix4() - traj.poses[i].worldToCamera.matrix4()).norm(),
        1e-12);
  }
}

TEST(TumTrajectory, StoresCameraPoseInTheWorld) {
  // A camera 2 m along +z looking back (identity rotation): world->camera t = -C.
  const auto dir = test::freshTempDir("Tum_Convention");
  std::ofstream(dir / "t.txt") << "# comment\n0.5 0 0 2 0 0 0 1\n";
  const TumTrajectory t = TumTrajectory::load(dir / "t.txt");
  ASSERT_EQ(t.poses.size(), 1u);
  EXPECT_NEAR(t.poses[0].worldToCamera.translation().z(), -2.0, 1e-12);
  EXPECT_TRUE(t.poseAt(0.5).has_value());
  EXPECT_FALSE(t.poseAt(0.6).has_value());
}

TEST(TumTrajectory, MalformedLinesNameTheLine) {
  const auto dir = test::freshTempDir("Tum_Malformed");
  std::ofstream(dir / "short.txt") << "0 0 0 0 0 0 0 1\n1 2 3\n";
  std::ofstream(dir / "nan.txt") << "0 nan 0 0 0 0 0 1\n";
  std::ofstream(dir / "quat.txt") << "0 0 0 0 0 0 0 3\n";
  auto message = [&](const char* name) {
    try {
      TumTrajectory::load(dir / name);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("short.txt").find("line 2"), std::string::npos);
  EXPECT_NE(message("nan.txt").find("NaN"), std::string::npos);
  EXPECT_NE(message("quat.txt").find("unit length"), std::string::npos);
  EXPECT_NE(message("missing.txt").find("cannot be opened"), std::string::npos);
}
