#pragma once
// PatchAligner: frame-side sub-pixel alignment of a warped reference window (issue 24 item 3, as
// PTAM aligns its patches). The template is the source image sampled around `sourceCentre`
// through a 2x2 map J (target-window offset -> source offset: the local affine of the predicted
// warp, e.g. W of Eq. 18 or a plane-induced homography); the target position whose window matches
// it is found by inverse-compositional Lucas-Kanade on the translation, with both windows
// normalised to zero mean and unit variance (exposure and contrast differ between the reference
// photo and the frame). The result is where the source point `sourceCentre` lies in the target,
// consistent with the source pixel rather than with an independently detected target corner.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace reftrack {

struct PatchAlignerParams {
  int halfWindow = 7;        // the windows are (2n+1)^2 pixels
  int maxIterations = 40;    // Gauss-Newton steps on the translation
  double epsilonPx = 0.005;  // stop when a step is smaller than this
  double maxShiftPx = 3.0;   // a point that moves farther than this from its start fails
  // A template whose gradient matrix has a smaller eigenvalue below this (per pixel, in units of
  // the normalised window: unit variance) has no position to align: flat or an edge.
  double minGradientEigenvalue = 0.02;
  // Normalised cross-correlation of the aligned windows below this: the alignment is refused.
  double minScore = 0.6;
  void check() const;  // throws reftrack::Error naming the bad field
};

struct PatchAlignment {
  cv::Point2f position;  // in the target (pixels)
  double score = 0.0;    // NCC of the aligned windows
  // Standard deviation (pixels, per axis, RMS of the two) of `position` predicted from the
  // window's gradients and the residual left after alignment: sigma^2 = SSE / (N - 2) *
  // trace((G^T G)^-1) / 2, G the template gradient (normalised units).
  double sigmaPx = 0.0;
};

class PatchAligner {
 public:
  explicit PatchAligner(PatchAlignerParams params = {});

  // source, target: CV_8UC1. J maps target offsets to source offsets. nullopt: the template or
  // the target window leaves its image, the template is flat, the alignment diverges or moves
  // more than maxShiftPx, or the aligned windows correlate below minScore.
  std::optional<PatchAlignment> align(const cv::Mat& source, cv::Point2d sourceCentre,
                                      const cv::Matx22d& J, const cv::Mat& target,
                                      cv::Point2d start) const;

  const PatchAlignerParams& params() const { return params_; }

 private:
  PatchAlignerParams params_;
  // Scratch (per aligner: an aligner is used by one thread at a time).
  mutable std::vector<float> templ_, t_, gx_, gy_, window_;
};

}  // namespace reftrack
