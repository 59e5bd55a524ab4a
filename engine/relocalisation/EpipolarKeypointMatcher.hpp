#pragma once
// EpipolarKeypointMatcher (issue 24 item 2): keypoint matches between two views whose poses are
// known, guided by the epipolar geometry. A keypoint of view i is compared only with the
// keypoints of view j near its epipolar line (both ways, within each keypoint's pixel tolerance),
// and keeps the nearest descriptor among them when it is mutual, clearly nearer than the
// runner-up among the same candidates (ratio) and not farther than an absolute bound. Ratio tests
// against a whole image reject nearly every keypoint of a repeated texture (a chessboard, tiles,
// a keyboard), whose twins lie off the line; along the line few remain, so many more keypoints
// of such scenes get a match (shared desk clip, references 0 and 40: 124 -> several hundred
// triangulated keypoints per reference).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack {

struct EpipolarKeypointMatcherParams {
  double ratio = 0.8;  // nearest < ratio * second nearest among the epipolar candidates
  // Absolute bound on the descriptor distance, as a fraction of the largest possible (binary:
  // the bit count; float: twice the descriptor's norm bound, 512 for SIFT's): a lone candidate
  // on the line must still look alike.
  double maxDistanceFraction = 0.2;
};

// ideal*: undistorted pixels of the keypoints; tolerance*: each keypoint's epipolar tolerance
// (pixels); F maps a pixel of i to its line in j (x_j^T F x_i = 0). Descriptors: one row per
// keypoint (CV_8U binary or CV_32F). Returns (i, j) index pairs.
std::vector<std::pair<int, int>> matchAlongEpipolarLines(
    const Eigen::Matrix3d& F, const std::vector<cv::Point2f>& idealI,
    const std::vector<double>& toleranceI, const cv::Mat& descriptorsI,
    const std::vector<cv::Point2f>& idealJ, const std::vector<double>& toleranceJ,
    const cv::Mat& descriptorsJ, int normType, const EpipolarKeypointMatcherParams& params = {});

}  // namespace reftrack
