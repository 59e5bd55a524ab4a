#pragma once
// ExposureIntegration: the time structure of one frame of a rolling-shutter camera and the image
// it records. Row r of frame k is exposed during [c - E/2, c + E/2] (frame periods), centred on
// c = k + (r - (rows - 1) / 2) * lineDelay, so the middle row's mid-exposure is frame time k:
// where the exact ground-truth pose of frame k lies. The image is built from renders of the real
// path at evenly spaced times spanning the frame: each row is the mean over its exposure window
// of the piecewise-linear interpolation (in time) of the renders — motion blur integrated over
// the exposure, rolling shutter as every row seen at its own time.
#include <functional>
#include <opencv2/core.hpp>

namespace reftrack::app {

struct RowExposureTiming {
  int rows = 1;
  double exposureFrames = 0.0;   // E, in frame periods (exposure seconds * fps)
  double lineDelayFrames = 0.0;  // row-to-row start delay, frame periods
  double rowCentre(double frameTime, int row) const;  // c above
  double span() const;  // from the first row's exposure start to the last row's end
  // Renders per frame when none is given: one per 1/8 frame period of the span (the image moves
  // 0.5 px between renders at 4 px per frame, interpolated linearly), at least 3; 1 when span()
  // is 0.
  int automaticSamples() const;
  void check() const;  // throws reftrack::Error for a bad value
};

// CV_32FC3 image of frame time `frameTime` from `samples` (>= 1) calls of renderAt(t) (CV_8UC3 or
// CV_32FC3, all of one size with timing.rows rows) at times evenly spanning the frame; samples 1
// renders once at frameTime. Throws reftrack::Error on a size mismatch.
cv::Mat integrateExposure(const std::function<cv::Mat(double frameTime)>& renderAt,
                          double frameTime, const RowExposureTiming& timing, int samples);

}  // namespace reftrack::app
