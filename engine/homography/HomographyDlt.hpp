#pragma once
// Normalised DLT (paper Sec. 3.2, Eq. 5-6; Hartley's normalisation): the homography H with
// dst ~ H src from at least 4 correspondences, each set translated to its centroid and scaled to
// a mean distance of sqrt(2) before solving ~p' x H~p = 0 (two rows per match) in least
// squares. Also: point transfer and the transfer error used by RANSAC and the refinement.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace reftrack {

// nullopt when fewer than 4 points, non-finite input, or a degenerate (collinear) set.
// `indices` selects a subset (all points when empty). H is scaled to h33 = 1 unless h33 ~ 0
// (then to unit Frobenius norm).
std::optional<cv::Matx33d> homographyDlt(const std::vector<cv::Point2f>& src,
                                         const std::vector<cv::Point2f>& dst,
                                         const std::vector<int>& indices = {});

// The exact homography of 4 correspondences src[sample[k]] -> dst[sample[k]] (h33 = 1), from the
// 8x8 linear system in normalised coordinates: the minimal solver of RANSAC, ~20x cheaper than
// the general DLT's 9x9 eigen-decomposition. nullopt when three of the points (in either image)
// are nearly collinear or the system is singular.
std::optional<cv::Matx33d> homographyFromFourPoints(const std::vector<cv::Point2f>& src,
                                                    const std::vector<cv::Point2f>& dst,
                                                    const int sample[4]);

// H applied to a point (nullopt-free: returns NaN when the point maps to infinity).
cv::Point2d transferPoint(const cv::Matx33d& H, cv::Point2d p);
// Jacobian of p -> H p (dehomogenised) at p: H's local affine map there.
cv::Matx22d transferJacobian(const cv::Matx33d& H, cv::Point2d p);
// Euclidean transfer error |H src - dst| in pixels.
double transferError(const cv::Matx33d& H, cv::Point2f src, cv::Point2f dst);

// The similarity that moves the points' centroid to the origin with mean distance sqrt(2).
cv::Matx33d normalisingTransform(const std::vector<cv::Point2f>& points,
                                 const std::vector<int>& indices = {});

}  // namespace reftrack
