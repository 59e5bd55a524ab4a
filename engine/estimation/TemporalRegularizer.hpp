#pragma once
// TemporalRegularizer (paper Sec. 5.2, SPEC §3): the frame-to-frame recursion around the pose
// estimator. Frame 1 (or after reset): standard least squares from the linear start, Omega_1 from
// its Jacobian. Frame k > 1: x_pred from the AR(p) model, Omega_pred = Omega_{k-1} + Q,
// x_k = argmin e_r (Eq. 13) started at x_pred, Omega_k = (J^T J)^-1. With the standard estimator
// selected every frame is solved by Eq. 12 from the previous estimate (the paper's comparison).
#include <deque>
#include <optional>
#include <utility>

#include "engine/config/PoseParams.hpp"  // PoseEstimatorKind
#include "engine/estimation/MotionModel.hpp"
#include "engine/estimation/RegularizedPoseEstimator.hpp"

namespace reftrack {

class TemporalRegularizer {
 public:
  TemporalRegularizer(ArMotionModel model, PoseEstimatorKind kind, double alpha);

  // One frame. `linearStart` is used on the first frame after a reset (and as a fallback when no
  // history exists). Returns nullopt when there is nothing to start from.
  std::optional<PoseEstimate> step(const RegularizedPoseEstimator& estimator,
                                   const PoseMeasurements& m,
                                   const std::optional<Vector6d>& linearStart);
  // The last step() again on other measurements (the same frame with outliers dropped), from the
  // state before it; nullopt (and nothing changed) when there was no step since the last reset.
  std::optional<PoseEstimate> redoLastStep(const RegularizedPoseEstimator& estimator,
                                           const PoseMeasurements& m,
                                           const std::optional<Vector6d>& linearStart);
  void reset();
  bool hasHistory() const { return !history_.empty(); }
  // Prediction for the next frame (for guided matching); nullopt without history.
  std::optional<Vector6d> predictNext() const;

  void setModel(ArMotionModel model) { model_ = std::move(model); }
  void setKind(PoseEstimatorKind kind) { kind_ = kind; }
  void setAlpha(double alpha) { alpha_ = alpha; }

 private:
  ArMotionModel model_;
  PoseEstimatorKind kind_;
  double alpha_;
  std::deque<Vector6d> history_;  // front = x_{k-1}
  Matrix6d omega_ = Matrix6d::Identity();
  // The state before the last step (redoLastStep), valid until the next reset.
  std::optional<std::pair<std::deque<Vector6d>, Matrix6d>> beforeLastStep_;
};

}  // namespace reftrack
