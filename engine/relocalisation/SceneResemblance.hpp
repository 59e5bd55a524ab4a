#pragma once
// SceneResemblance: how much a frame looks like one of the map's reference views, judged from
// small blurred images of both (as PTAM's relocaliser compares its keyframes' small blurry
// images): 0.2 ms at 752x480, so a lost tracker can ask on every frame whether the scene
// may be back, and spend a search then rather than whenever its time budget next allows.
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack {

class SceneResemblance {
 public:
  // views: the reference images (8- or 16-bit grey, BGR or BGRA, as the tracker takes frames; one
  // size). Throws reftrack::Error for an empty or unsupported image or views of different sizes.
  explicit SceneResemblance(const std::vector<cv::Mat>& views);

  // The highest zero-mean normalised cross-correlation of the frame's small image with a view's,
  // over shifts of up to two of its pixels (3-5% of the width) each way: 1 for the view itself,
  // about 0 for an unrelated scene. -1 for a frame without contrast (black, uniform). The frame
  // (as a view) may have any size; it is reduced to the views' small size.
  double score(const cv::Mat& frame) const;

  // Small images are the views reduced by an integer factor to 40-79 pixels wide.
  static constexpr int kWidth = 40;
  static constexpr int kMaxShift = 2;        // the shifts tried, in small-image pixels
  static constexpr double kBlurSigma = 1.0;  // Gaussian blur of the small images (their pixels)
  // What score() costs, modelled as RecoveryWork's units are (CPU ms of one core of the
  // development machine, per megapixel of frame; measured with two views at 752x480: 0.21 ms).
  static constexpr double kModelledMsPerMegapixel = 0.6;

 private:
  cv::Size size_, firstSize_;   // the small images' size, the views'
  int factor_ = 1;              // views' size / small size (an integer)
  std::vector<cv::Mat> views_;  // CV_32F small images, blurred
  cv::Mat small(const cv::Mat& image) const;
};

}  // namespace reftrack
