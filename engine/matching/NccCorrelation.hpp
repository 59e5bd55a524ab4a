#pragma once
// NCC correlation (Eq. 17). NccPatches: (2n+1)^2 grey-level windows around a set of points, stored
// contiguously and already reduced to zero mean and unit norm, so the normalised cross-correlation
// of Eq. 17,
//   sum (I1 - mean1)(I2 - mean2) / ((2n+1)^2 sd1 sd2),
// of two windows is one dot product. A window that leaves the image or is flat (sd = 0) is
// invalid and scores -1 against everything.
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack {

class NccPatches {
 public:
  explicit NccPatches(int halfWindow = 5);

  // Square windows centred on the nearest pixel of each centre (Eq. 17). gray: CV_8UC1.
  static NccPatches square(const cv::Mat& gray, const std::vector<cv::Point2f>& centres,
                           int halfWindow);
  // Warped windows (Eq. 19): window pixel m (offset from the centre) is sampled bilinearly at
  // centre_i + A_i m, A_i the local linear map (e.g. a homography's Jacobian) of point i.
  static NccPatches warped(const cv::Mat& gray, const std::vector<cv::Point2f>& centres,
                           const std::vector<cv::Matx22f>& maps, int halfWindow);

  int size() const { return static_cast<int>(valid_.size()); }
  int halfWindow() const { return half_; }
  int area() const { return area_; }  // pixels per window; patch(i) holds them in order
  bool valid(int i) const { return valid_[static_cast<size_t>(i)] != 0; }
  const float* patch(int i) const { return data_.data() + static_cast<size_t>(i) * stride_; }

  // NCC in [-1, 1] of patch i here and patch j of `other` (same window size); -1 if invalid.
  float score(int i, const NccPatches& other, int j) const;

 private:
  static constexpr int kLanes = 8;  // patches are zero-padded to a multiple of this
  void normaliseLast(int i);
  int half_, area_, stride_;
  std::vector<float> data_;
  std::vector<char> valid_;
};

// Eq. 17 evaluated directly on two images at integer centres (reference for tests and for
// one-off scores); -1 when a window leaves its image or is flat.
double nccAt(const cv::Mat& gray1, cv::Point c1, const cv::Mat& gray2, cv::Point c2,
             int halfWindow);

}  // namespace reftrack
