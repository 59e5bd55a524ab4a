// readEurocGroundTruth: body poses through T_BS to camera poses, ns timestamps, clear errors.
#include "engine/dataset/EurocGroundTruth.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "DatasetFixtures.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
namespace fs = std::filesystem;

TEST(EurocGroundTruth, CameraPoseIsBodyPoseTimesTbs) {
  const fs::path dir = test::freshTempDir("EurocGroundTruth_ok");
  fs::create_directories(dir);
  // Body at (1, 2, 3) turned 90 degrees about z; camera 0.1 m along the body's x, turned 90
  // degrees about x (T_BS).
  std::ofstream(dir / "data.csv")
      << "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
         "q_RS_z [], v..., b...\n"
      << "1403636580838555648,1,2,3,0.70710678118654757,0,0,0.70710678118654757,0,0,0,0,0,0,0,0,"
         "0\n";
  const RigidPose tbs(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX())),
                      Eigen::Vector3d(0.1, 0, 0));
  const TumTrajectory t = readEurocGroundTruth(dir / "data.csv", tbs);
  ASSERT_EQ(t.poses.size(), 1u);
  EXPECT_NEAR(t.poses[0].timestamp, 1403636580.838555648, 3e-7);
  // Camera centre: body origin + R_z(90) * (0.1, 0, 0) = (1, 2.1, 3).
  EXPECT_LT((t.poses[0].worldToCamera.cameraCentre() - Eigen::Vector3d(1, 2.1, 3)).norm(), 1e-12);
  // The camera's z axis (optical axis) in the world: R_z(90) R_x(90) e_z = R_z(90) (0,-1,0) =
  // (1,0,0).
  const Eigen::Vector3d axis = t.poses[0].worldToCamera.rotation().transpose().col(2);
  EXPECT_LT((axis - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
}

TEST(EurocGroundTruth, BadFilesAreClearErrors) {
  const fs::path dir = test::freshTempDir("EurocGroundTruth_bad");
  auto errorOf = [&](const std::string& content) {
    std::ofstream(dir / "data.csv") << content;
    try {
      readEurocGroundTruth(dir / "data.csv", RigidPose());
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(errorOf("#header\n1,2,3\n").find("line 2"), std::string::npos);
  EXPECT_NE(errorOf("1,0,0,0,2,0,0,0\n").find("not unit length"), std::string::npos);
  EXPECT_NE(errorOf("2,0,0,0,1,0,0,0\n1,0,0,0,1,0,0,0\n").find("does not increase"),
            std::string::npos);
  EXPECT_NE(errorOf("#only a header\n").find("holds no pose"), std::string::npos);
  EXPECT_THROW(readEurocGroundTruth(dir / "missing.csv", RigidPose()), Error);
}
