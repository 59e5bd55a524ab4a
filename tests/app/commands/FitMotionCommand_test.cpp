#include <gtest/gtest.h>

#include <random>

#include "app/commands/CommandTestSupport.hpp"
#include "engine/core/Error.hpp"
#include "engine/estimation/MotionModelFile.hpp"
#include "engine/geometry/TumTrajectory.hpp"

using namespace reftrack;

TEST(FitMotionCommand, RecoversAr2WeightsFromATrajectoryFile) {
  const auto dir = test::freshTempDir("FitMotionCommand_Ar2");
  // Every component follows x_k = 1.5 x_{k-1} - 0.6 x_{k-2} + e_k; poses T_k = exp(x_k) T_1.
  std::mt19937 rng(3);
  std::normal_distribution<double> e(0.0, 0.002);
  std::vector<Vector6d> x(3000, Vector6d::Zero());
  for (std::size_t k = 2; k < x.size(); ++k)
    for (int c = 0; c < 6; ++c) x[k][c] = 1.5 * x[k - 1][c] - 0.6 * x[k - 2][c] + e(rng);
  Vector6d first;
  first << 0.0, 0.1, 0.5, 0.3, 0.0, 0.1;
  TumTrajectory traj;
  for (std::size_t k = 0; k < x.size(); ++k)
    traj.poses.push_back({k / 30.0, RigidPose::fromVector6(x[k]) * RigidPose::fromVector6(first)});
  traj.save(dir / "traj.txt");

  const auto r = test::runReftrack("fit-motion --trajectory " + (dir / "traj.txt").string() +
                                       " --order 2 --out " + (dir / "motion.yml").string(),
                                   dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("explained"), std::string::npos);
  const FittedMotionModel fit = loadMotionModel(dir / "motion.yml");
  ASSERT_EQ(fit.model.order(), 2);
  EXPECT_EQ(fit.frameCount, 3000);
  EXPECT_EQ(fit.sourceTrajectory, "traj.txt");
  // The bar: within 0.05. The TUM file keeps 17 significant digits, so the file adds
  // nothing measurable to the least-squares error (~0.015 for 3000 samples).
  for (int c = 0; c < 6; ++c) {
    EXPECT_NEAR(fit.model.weights()[0][c], 1.5, 0.05) << c;
    EXPECT_NEAR(fit.model.weights()[1][c], -0.6, 0.05) << c;
  }
}

TEST(FitMotionCommand, UsageAndRuntimeErrors) {
  const auto dir = test::freshTempDir("FitMotionCommand_Errors");
  EXPECT_EQ(test::runReftrack("fit-motion --trajectory missing.txt --out m.yml", dir).exitCode, 2);
  TumTrajectory shortTraj;
  for (int k = 0; k < 4; ++k) shortTraj.poses.push_back({k * 0.1, RigidPose()});
  shortTraj.save(dir / "short.txt");
  const auto r = test::runReftrack("fit-motion --trajectory " + (dir / "short.txt").string() +
                                       " --out " + (dir / "m.yml").string(),
                                   dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("needs at least"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "m.yml"));
}
