#include "engine/estimation/RollingShutterEstimator.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {
// Frames whose rows' shifts are this small (information g^T W P g per frame, i.e. squared
// readout-SDs^-1) carry no usable signal: a camera at rest.
constexpr double kMinFrameInformation = 1.0;
// Huber threshold on the normalised residual: a few mismatched corners do not steer the step.
constexpr double kHuber = 3.0;
// The estimate replaces the start value only once it is this many SDs away from it...
constexpr double kSignificance = 3.0;
// ... with an SD no larger than this (the simulated webcam at 320x240: 0.07 after ten frames).
constexpr double kEngageSd = 0.1;
// SD of the prior around the start value (a readout is between 0 and 1 frame intervals).
constexpr double kPriorSd = 0.2;
// Per-frame weight of the past: about the last 100 informative frames count.
constexpr double kForgetting = 0.99;
}  // namespace

RollingShutterEstimator::RollingShutterEstimator(double initialReadout, int minFrames)
    : initial_(initialReadout), readout_(initialReadout), minFrames_(minFrames) {
  if (!(initialReadout >= 0.0 && initialReadout <= 1.0))
    throw Error("RollingShutterEstimator: the initial readout must be in [0, 1]");
  if (minFrames < 1) throw Error("RollingShutterEstimator: minFrames must be >= 1");
}

void RollingShutterEstimator::reset(double initialReadout) {
  *this = RollingShutterEstimator(initialReadout, minFrames_);
}

void RollingShutterEstimator::addFrame(double fx, double fy,
                                       const std::vector<RollingShutterObservation>& observations) {
  if (observations.size() < 8) return;
  // Normal equations of [J g] under weights W, J the residual's derivative with respect to a
  // small camera-frame motion (rotation w, translation t: X' = X + w x X + t).
  using Matrix7d = Eigen::Matrix<double, 7, 7>;
  using Vector7d = Eigen::Matrix<double, 7, 1>;
  Matrix7d N = Matrix7d::Zero();
  Vector7d b = Vector7d::Zero();
  double eWe = 0.0;
  for (const RollingShutterObservation& o : observations) {
    const Eigen::Vector3d& X = o.pointCamera;
    if (!(X.z() > 1e-9) || !o.residual.allFinite() || !o.perReadout.allFinite()) continue;
    const double iz = 1.0 / X.z();
    Eigen::Matrix<double, 2, 3> dp;  // d projection / d X
    dp << fx * iz, 0.0, -fx * X.x() * iz * iz, 0.0, fy * iz, -fy * X.y() * iz * iz;
    Eigen::Matrix3d skew;
    skew << 0.0, -X.z(), X.y(), X.z(), 0.0, -X.x(), -X.y(), X.x(), 0.0;
    Eigen::Matrix<double, 2, 7> A;
    A.leftCols<3>() = -dp * skew;  // rotation
    A.block<2, 3>(0, 3) = dp;      // translation
    A.col(6) = o.perReadout;
    double w = 1.0 / (o.sigmaPx * o.sigmaPx);
    const double normalised = o.residual.norm() * std::sqrt(w);
    if (normalised > kHuber) w *= kHuber / normalised;
    N.noalias() += w * A.transpose() * A;
    b.noalias() += w * A.transpose() * o.residual;
    eWe += w * o.residual.squaredNorm();
  }
  // Schur complement of the pose block: the readout's information and gradient with the pose
  // free to absorb whatever it can.
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> pose(N.topLeftCorner<6, 6>());
  if (pose.info() != Eigen::Success) return;
  const Eigen::Matrix<double, 6, 1> Jg = N.block<6, 1>(0, 6);
  const Eigen::Matrix<double, 6, 1> Je = b.head<6>();
  const double information = N(6, 6) - Jg.dot(pose.solve(Jg));
  const double gradient = b(6) - Jg.dot(pose.solve(Je));
  const double chi2 = eWe - Je.dot(pose.solve(Je));
  if (!std::isfinite(information) || !std::isfinite(gradient) || !std::isfinite(chi2)) return;
  if (information < kMinFrameInformation) return;
  // Recursive least squares with forgetting: older frames fade (the readout is the camera's, but
  // a camera's mode can change), and the sums stay those of the current readout: the residuals
  // are linear in it, so moving it by d moves the gradient by information * d.
  information_ = kForgetting * information_ + information;
  gradient_ = kForgetting * gradient_ + gradient;
  chi2_ = kForgetting * chi2_ + std::max(chi2, 0.0);
  dof_ = kForgetting * dof_ + 2.0 * static_cast<double>(observations.size()) - 7.0;
  if (++frames_ < minFrames_) return;
  // The least-squares readout and its SD, with the residual scale the frames show (real corners
  // are rarely as good as their modelled SD says).
  const double scale2 = dof_ > 0 ? std::max(chi2_ / dof_, 1e-12) : 1.0;
  const double sd = std::sqrt(scale2 / information_);
  const double leastSquares = readout_ - gradient_ / information_;
  // Until the data show the start value wrong beyond doubt (kSignificance SDs, with an SD of at
  // most kEngageSd), it stays: on the real postcard clip (a slow hand-held camera, a guessed K)
  // the estimate wanders between -0.15 and 0.8 with SDs of 0.1-0.4, and following it, even
  // shrunk, cost 0.014 px of cube error.
  if (!engaged_) {
    if (!(sd <= kEngageSd && std::abs(leastSquares - initial_) >= kSignificance * sd)) return;
    engaged_ = true;
  }
  // Shrunk towards the start value by a prior of SD kPriorSd: a weakly determined estimate (few
  // or slow frames, a small image) moves the readout only part of the way.
  const double w = 1.0 / (sd * sd), w0 = 1.0 / (kPriorSd * kPriorSd);
  const double next = std::clamp((w0 * initial_ + w * leastSquares) / (w0 + w), 0.0, 1.0);
  gradient_ += information_ * (next - readout_);
  readout_ = next;
  sd_ = sd;
  ++updates_;
}

}  // namespace reftrack
