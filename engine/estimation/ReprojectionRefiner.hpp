#pragma once
// ReprojectionRefiner: the pose (OpenCV rvec/tvec, world to camera) that minimises the squared
// reprojection error of 3D-2D pairs through K (no distortion), by Gauss-Newton (damped when a
// step fails) from a pose near it, as RANSAC or SQPnP give: the objective of
// cv::solvePnPRefineLM for a fraction of its cost (PoseTracker's outlier rejection).
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack {

// Refines rvec/tvec in place over at most `maxIterations` steps; a step that does not lower the
// squared error is retried damped (Levenberg, up to 6 times) and otherwise ends the refinement,
// one that lowers it by less than a part in 1e10 is the last. Returns the steps taken. Pairs behind
// the camera are left out of a step; with fewer than 3 usable pairs nothing changes.
int refineReprojection(const std::vector<cv::Point3d>& object,
                       const std::vector<cv::Point2d>& image, const cv::Matx33d& K, cv::Vec3d& rvec,
                       cv::Vec3d& tvec, int maxIterations = 10);

}  // namespace reftrack
