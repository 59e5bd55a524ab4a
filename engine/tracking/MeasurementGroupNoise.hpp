#pragma once
// MeasurementGroupNoise: how noisy each kind of pose measurement is on this camera, learned from
// the tracked frames. The corner-variance model (paper Fig. 7) gives every corner's SD on an ideal
// sharp corner; a real camera's blur, compression, rolling shutter and the map's own errors make
// each kind of term worse by its own factor (ViSP's desk camera: epipolar terms 20-200 times their
// modelled variance, corner map points 5-40, keypoint points 1-5), so weighted by the model alone
// the wrong kind dominates. Each accepted frame gives each kind's median whitened squared residual
// over its chi-square median (a robust variance factor); the factors are averaged with a forgetting
// factor over about `frames` frames. Weights use the factors relative to their geometric mean, so
// the measurements' overall weight against the motion prior is kept; the mean itself says how far
// the whole model is off.
#include <array>
#include <vector>

namespace reftrack {

enum class MeasurementGroup { CornerPoints = 0, KeypointPoints = 1, EpipolarA = 2, EpipolarB = 3 };
inline constexpr int kMeasurementGroups = 4;

class MeasurementGroupNoise {
 public:
  // frames <= 0 turns the learning off (every factor 1).
  explicit MeasurementGroupNoise(double frames = 10.0) : frames_(frames) {}

  // The multiplier of a term's modelled variance for its group: 1 until the group has been seen.
  double varianceFactor(MeasurementGroup group) const;
  // The geometric mean of the seen groups' absolute factors (1 when none has been seen).
  double meanAbsoluteFactor() const;
  // One accepted frame: per group, its terms' squared residual norms whitened by their modelled
  // variance alone (without this group factor; residualDimension gives their dimension). A group
  // with fewer than kMinTerms terms this frame keeps its factor.
  struct FrameResiduals {
    std::array<std::vector<double>, kMeasurementGroups> whitenedSquared;
  };
  void observe(FrameResiduals residuals);

  void setFrames(double frames) { frames_ = frames; }
  void clear();

  static constexpr int kMinTerms = 5;

 private:
  double frames_;
  std::array<double, kMeasurementGroups> absolute_{1.0, 1.0, 1.0, 1.0};
  std::array<bool, kMeasurementGroups> seen_{false, false, false, false};
};

// The dimension of a group's residuals (2 for the points' reprojections, 1 for the epipolar
// distances).
int residualDimension(MeasurementGroup group);

}  // namespace reftrack
