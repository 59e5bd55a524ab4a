#pragma once
// motion.yml: a fitted AR(p) motion model (paper Sec. 5.3) as written by `reftrack fit-motion`
// and loaded by the tracker and the viewer. OpenCV FileStorage YAML with the keys
//   kind ("ar" or "random_walk"), order, weights (order x 6: row j = diagonal of Q_{j+1}),
//   Q (6x6), explained_variance (6, per component), source_trajectory, frame_count.
#include <filesystem>
#include <string>

#include "engine/estimation/MotionModel.hpp"

namespace reftrack {

struct FittedMotionModel {
  ArMotionModel model;
  bool randomWalk = false;  // p = 0: x_pred = x_{k-1}, Q = covariance of dx_k (SPEC §3)
  Vector6d explainedVariance = Vector6d::Zero();  // 1 - var(residual) / var(x), per component
  std::string sourceTrajectory;
  int frameCount = 0;
};

// Atomic write.
void saveMotionModel(const std::filesystem::path& file, const FittedMotionModel& fitted);
// Throws reftrack::Error naming the file and the missing or bad field.
FittedMotionModel loadMotionModel(const std::filesystem::path& file);

}  // namespace reftrack
