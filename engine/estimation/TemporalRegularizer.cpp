#include "engine/estimation/TemporalRegularizer.hpp"

namespace reftrack {

TemporalRegularizer::TemporalRegularizer(ArMotionModel model, PoseEstimatorKind kind, double alpha)
    : model_(std::move(model)), kind_(kind), alpha_(alpha) {}

void TemporalRegularizer::reset() {
  history_.clear();
  omega_ = Matrix6d::Identity();
  beforeLastStep_.reset();
}

std::optional<PoseEstimate> TemporalRegularizer::redoLastStep(
    const RegularizedPoseEstimator& estimator, const PoseMeasurements& m,
    const std::optional<Vector6d>& linearStart) {
  if (!beforeLastStep_) return std::nullopt;
  history_ = beforeLastStep_->first;
  omega_ = beforeLastStep_->second;
  return step(estimator, m, linearStart);
}

std::optional<Vector6d> TemporalRegularizer::predictNext() const {
  if (history_.empty()) return std::nullopt;
  return model_.predict(history_);
}

std::optional<PoseEstimate> TemporalRegularizer::step(const RegularizedPoseEstimator& estimator,
                                                      const PoseMeasurements& m,
                                                      const std::optional<Vector6d>& linearStart) {
  beforeLastStep_.emplace(history_, omega_);
  PoseEstimate e;
  if (history_.empty()) {
    if (!linearStart) return std::nullopt;
    e = estimator.estimateStandard(m, *linearStart);
  } else if (kind_ == PoseEstimatorKind::Standard) {
    e = estimator.estimateStandard(m, history_.front());
  } else {
    const Vector6d xPred = model_.predict(history_);
    const Matrix6d omegaPred = omega_ + model_.processNoise();
    e = estimator.estimateRegularised(m, xPred, omegaPred, alpha_);
    // A solve from x_pred that does not converge, or spends its iteration budget (Ceres counts
    // the start as an iteration: maxIterations - 1 steps or more), is on a long path between two
    // minima (ViSP frame 81: 19-25 iterations, minima 24 mm / 1.4 degrees apart): it is solved
    // again from the linear start and the lower cost kept. Not always: the lower cost of both
    // starts picks a look-alike pose on repeated texture (research README).
    if (linearStart && (!e.converged || e.iterations >= estimator.options().maxIterations)) {
      const PoseEstimate fromLinear =
          estimator.estimateRegularised(m, xPred, omegaPred, alpha_, linearStart);
      if (fromLinear.x.allFinite() && fromLinear.finalCost < e.finalCost) e = fromLinear;
    }
  }
  if (!e.x.allFinite()) return std::nullopt;
  if (e.covarianceValid) omega_ = e.covariance;
  history_.push_front(e.x);
  while (static_cast<int>(history_.size()) > std::max(1, model_.order())) history_.pop_back();
  return e;
}

}  // namespace reftrack
