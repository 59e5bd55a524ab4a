#pragma once
// RollingShutterEstimator: the sensor's rolling-shutter readout (first row to last, as a fraction
// of the frame interval) estimated online from tracked frames. A frame's measurements move by
// readout * g (g: the row's share of its frame-to-frame motion, RollingShutterObservation), so
// its residuals at the tracked pose are linear in the readout; the pose's six degrees of freedom
// are projected out of them (a Schur complement), leaving what no pose explains. Frames without
// motion carry no information and change nothing. Recursive weighted least squares over the
// informative frames (older ones fading): from `minFrames` of them on, once their solution differs
// from the start value significantly, the readout follows it, shrunk towards the start value by
// how uncertain it still is, clamped to [0, 1]; a global-shutter camera stays at 0.
#include <Eigen/Core>
#include <vector>

namespace reftrack {

struct RollingShutterObservation {
  Eigen::Vector3d pointCamera;  // the 3D point in the camera frame, at the tracked pose
  Eigen::Vector2d residual;     // projection minus the (readout-corrected) measurement, pixels
  Eigen::Vector2d perReadout;   // d residual / d readout: the measurement's shift per unit readout
  double sigmaPx = 1.0;         // measurement SD, pixels
};

class RollingShutterEstimator {
 public:
  explicit RollingShutterEstimator(double initialReadout = 0.0, int minFrames = 10);

  // One tracked frame's three-view observations; fx, fy: the pinhole's focal lengths (pixels).
  void addFrame(double fx, double fy, const std::vector<RollingShutterObservation>& observations);
  double readout() const { return readout_; }
  int updates() const { return updates_; }  // frames whose solution was taken
  double sd() const { return sd_; }         // least-squares SD at the last update (0: none yet)
  int frames() const { return frames_; }    // informative frames so far
  void reset(double initialReadout);

 private:
  double initial_;
  double readout_;
  int minFrames_;
  double information_ = 0.0;  // fading sum of g^T W P g
  double gradient_ = 0.0;     // sum of g^T W P e
  double chi2_ = 0.0;         // sum of e^T W P e (for the residual scale)
  double dof_ = 0.0;
  int frames_ = 0;
  int updates_ = 0;
  bool engaged_ = false;  // the data have shown the start value wrong
  double sd_ = 0.0;
};

}  // namespace reftrack
