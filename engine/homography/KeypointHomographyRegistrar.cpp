#include "engine/homography/KeypointHomographyRegistrar.hpp"

#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"

namespace reftrack {

namespace {

const HomographyTrackerParams& checked(const HomographyTrackerParams& p, const RansacParams& r) {
  p.check();
  r.check();
  if (p.keypoints == KeypointLayer::None)
    throw Error("keypoint registrar: homography.keypoints is 'none'");
  return p;
}

cv::Ptr<cv::Feature2D> makeDetector(const HomographyTrackerParams& p) {
  switch (p.keypoints) {
    case KeypointLayer::Orb:
      return cv::ORB::create(p.keypointFeatures);
    case KeypointLayer::Akaze:
      return cv::AKAZE::create();
    case KeypointLayer::Sift:
      return cv::SIFT::create(p.keypointFeatures);
    case KeypointLayer::None:
      break;
  }
  throw Error("keypoint registrar: no detector for homography.keypoints 'none'");
}

// RANSAC iterations and confidence of the keypoint homography (cv::findHomography): enough for a
// 10% inlier fraction at 99.5% confidence (log(0.005) / log(1 - 0.1^4) ~ 53000 is the worst
// case; OpenCV stops as soon as the inlier fraction found allows).
constexpr int kRansacIterations = 5000;
constexpr double kRansacConfidence = 0.995;

}  // namespace

KeypointHomographyRegistrar::KeypointHomographyRegistrar(const cv::Mat& reference,
                                                         const HomographyTrackerParams& params,
                                                         const RansacParams& ransac)
    : params_(checked(params, ransac)), ransac_(ransac), detector_(makeDetector(params_)) {
  if (reference.empty()) throw Error("keypoint registrar: the reference image is empty");
  norm_ = params_.keypoints == KeypointLayer::Sift ? cv::NORM_L2 : cv::NORM_HAMMING;
  detect(toGray8(reference), 1.0, refKeypoints_, refDescriptors_);
  if (static_cast<int>(refKeypoints_.size()) < ransac_.minInliers)
    throw Error("keypoint registrar: only " + std::to_string(refKeypoints_.size()) + " " +
                keypointLayerName(params_.keypoints) +
                " keypoints in the reference image (at least " +
                std::to_string(ransac_.minInliers) + " needed)");
}

void KeypointHomographyRegistrar::detect(const cv::Mat& gray, double scale,
                                         std::vector<cv::KeyPoint>& keypoints,
                                         cv::Mat& descriptors) const {
  cv::Mat image = gray;
  if (scale < 1.0) cv::resize(gray, image, cv::Size(), scale, scale, cv::INTER_AREA);
  detector_->detect(image, keypoints);
  cv::KeyPointsFilter::retainBest(keypoints, params_.keypointFeatures);
  detector_->compute(image, keypoints, descriptors);
  if (scale < 1.0)
    for (cv::KeyPoint& k : keypoints) {  // pixel centres: x_full = (x_small + 0.5) / s - 0.5
      k.pt.x = static_cast<float>((k.pt.x + 0.5) / scale - 0.5);
      k.pt.y = static_cast<float>((k.pt.y + 0.5) / scale - 0.5);
      k.size = static_cast<float>(k.size / scale);
    }
}

KeypointRegistration KeypointHomographyRegistrar::registerFrame(const cv::Mat& frame) const {
  if (frame.empty()) throw Error("keypoint registrar: the frame is empty");
  const cv::Mat gray = toGray8(frame);
  KeypointRegistration out;
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  detect(gray, params_.keypointDetectScale, keypoints, descriptors);
  out.frameKeypoints = static_cast<int>(keypoints.size());
  if (static_cast<int>(keypoints.size()) < ransac_.minInliers || refDescriptors_.empty()) {
    out.failure = "only " + std::to_string(keypoints.size()) + " keypoints in the frame";
    return out;
  }
  // All descriptor distances at once (frame rows x reference columns): the two nearest reference
  // keypoints of each frame keypoint (ratio test) and the nearest frame keypoint of each
  // reference keypoint (mutual check).
  cv::Mat distance;  // Hamming distances come as CV_32S (the only type OpenCV gives them in)
  cv::batchDistance(descriptors, refDescriptors_, distance,
                    norm_ == cv::NORM_HAMMING ? CV_32S : CV_32F, cv::noArray(), norm_);
  if (distance.type() != CV_32F) distance.convertTo(distance, CV_32F);
  const int rows = distance.rows, cols = distance.cols;
  std::vector<float> columnBest(static_cast<size_t>(cols), std::numeric_limits<float>::max());
  std::vector<int> columnArg(static_cast<size_t>(cols), -1);
  std::vector<int> rowArg(static_cast<size_t>(rows), -1);
  const float ratio = static_cast<float>(params_.keypointRatio);
  for (int r = 0; r < rows; ++r) {
    const float* d = distance.ptr<float>(r);
    float best = std::numeric_limits<float>::max(), second = best;
    int arg = -1;
    for (int c = 0; c < cols; ++c) {
      if (d[c] < best) {
        second = best;
        best = d[c];
        arg = c;
      } else if (d[c] < second) {
        second = d[c];
      }
      if (d[c] < columnBest[static_cast<size_t>(c)]) {
        columnBest[static_cast<size_t>(c)] = d[c];
        columnArg[static_cast<size_t>(c)] = r;
      }
    }
    if (arg >= 0 && best < ratio * second) rowArg[static_cast<size_t>(r)] = arg;
  }
  std::vector<cv::Point2f> src, dst;
  for (int r = 0; r < rows; ++r) {
    const int c = rowArg[static_cast<size_t>(r)];
    if (c < 0 || columnArg[static_cast<size_t>(c)] != r) continue;
    src.push_back(refKeypoints_[static_cast<size_t>(c)].pt);
    dst.push_back(keypoints[static_cast<size_t>(r)].pt);
  }
  out.matches = static_cast<int>(src.size());
  if (out.matches < ransac_.minInliers) {
    out.failure = "only " + std::to_string(out.matches) + " keypoint matches";
    return out;
  }
  std::vector<uchar> mask;
  const double threshold = params_.keypointInlierThresholdPx * resolutionScale(gray.size());
  const cv::Mat H = cv::findHomography(src, dst, cv::RANSAC, threshold, mask, kRansacIterations,
                                       kRansacConfidence);
  if (H.empty()) {
    out.failure = "no keypoint homography";
    return out;
  }
  for (uchar m : mask) out.inliers += m ? 1 : 0;
  out.H = cv::Matx33d(H) * (1.0 / H.at<double>(2, 2));
  if (out.inliers < ransac_.minInliers) {
    out.failure = "only " + std::to_string(out.inliers) + " keypoint inliers";
    return out;
  }
  // The view must be a plane in front of the camera (w > 0 at every inlier) and not degenerate
  // where the inliers are: the area ratio (Jacobian determinant) at their centroid within
  // [min_determinant, 1 / min_determinant]. (det H itself is the area ratio at the reference's
  // origin, which a zoomed, tilted view legitimately pushes past any bound.)
  cv::Point2d centroid(0, 0);
  bool inFront = true;
  for (size_t i = 0; i < src.size(); ++i) {
    if (!mask[i]) continue;
    centroid += cv::Point2d(src[i].x, src[i].y) * (1.0 / out.inliers);
    inFront = inFront && out.H(2, 0) * src[i].x + out.H(2, 1) * src[i].y + out.H(2, 2) > 0;
  }
  const double w =
      out.H(2, 0) * centroid.x + out.H(2, 1) * centroid.y + out.H(2, 2);  // area ratio: det/w^3
  const double areaRatio = cv::determinant(out.H) / (w * w * w);
  if (!inFront || !std::isfinite(areaRatio) || areaRatio < ransac_.minDeterminant ||
      areaRatio > 1.0 / ransac_.minDeterminant) {
    out.failure = "degenerate keypoint homography";
    return out;
  }
  out.found = true;
  return out;
}

}  // namespace reftrack
