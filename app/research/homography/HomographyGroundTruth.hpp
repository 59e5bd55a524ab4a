#pragma once
// Exact ground truth for homography-mode experiments. A camera that only rotates by R about its
// optical centre (X_frame = R X_ref) sees the reference through H = K R K^-1 (SPEC §5); the
// errors below compare an estimated H with that truth where it matters in the frame.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack::app {

// K R K^-1 (reference pixels -> frame pixels), scaled to h33 = 1.
cv::Matx33d rotationHomography(const Eigen::Matrix3d& K, const Eigen::Matrix3d& R);

// Fraction of the frame's pixels (sampled on a 64x48 grid) that see the reference image under
// the true reference -> frame homography; 0 when none (or when H maps behind the camera).
double overlapFraction(const cv::Matx33d& trueH, cv::Size size);

// Mean of |estimated H p - true H p| over the reference points p whose true image lies inside
// the frame; NaN when none does.
double meanTransferDeviation(const cv::Matx33d& estimatedH, const cv::Matx33d& trueH,
                             const std::vector<cv::Point2d>& referencePoints, cv::Size size);

// Registration error at the frame's four corners: for each corner c, |estimated H (true H^-1 c)
// - c| (where content drawn from the reference lands); the mean of the four, in pixels.
double frameCornerError(const cv::Matx33d& estimatedH, const cv::Matx33d& trueH, cv::Size size);

// Registration error at the reference's four corners (the Oxford benchmark's convention): the
// mean of |estimated H c - true H c| over the reference image's corners c, in frame pixels.
double referenceCornerError(const cv::Matx33d& estimatedH, const cv::Matx33d& trueH,
                            cv::Size referenceSize);

// A cols x rows grid of points spanning the image with a margin of one cell / 2 (annotation
// positions for the rotation sweep).
std::vector<cv::Point2d> annotationGrid(cv::Size size, int cols, int rows);

}  // namespace reftrack::app
