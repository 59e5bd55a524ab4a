#pragma once
// ReferenceBundleAdjuster (issue 13, `reftrack extend`): a Ceres bundle adjustment over a
// MultiReferenceMap that refines the world->camera poses of the non-anchored references
// (views[i].anchored == false, added from a video) and the 3D points, with the anchored
// references (marker / given poses) held constant, so the world frame never moves.
// Observations: every point's measured pixel in every reference that sees it (its correlation
// peak, the pixel it was triangulated from, or its corner where the map keeps no peak:
// MultiReferenceMap::measuredPixel), undistorted through the map's PinholeCamera; cost
// MapPointReprojectionCost under a robust loss (params.loss, scale
// params.lossScalePx); single-threaded.
// Gauge: with the anchored poses constant, a point seen by two anchored references is fixed by
// them; a non-anchored reference is refined only when it sees at least params.minDeterminedPoints
// points that two determined references see (anchored ones, then by closure over the refined
// ones), which pins its 6 DOF and its scale. Any other non-anchored reference is held where it is
// (its pose and scale would float) and the report says so. Points seen only by non-anchored
// references are refined too: their references are held or determined, so they are pinned.
// Observations behind their camera at the start are left out (counted in the report).
#include <vector>

#include "engine/config/BundleAdjustmentParams.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack {

struct ViewAdjustment {
  bool anchored = true;
  bool refined = false;  // false: anchored, or held because it is not determined (see gauge)
  int observations = 0;  // observations in the problem
  int outliers = 0;      // final reprojection error above params.outlierThresholdPx
  double initialRmsPx = 0.0, finalRmsPx = 0.0;  // over its inlier observations
  double movedMetres = 0.0, movedDeg = 0.0;     // camera centre shift and rotation change
};

struct BundleAdjustmentReport {
  int observations = 0;         // observations in the problem
  int skippedBehindCamera = 0;  // observations left out: point behind the camera at the start
  int outliers = 0;             // final reprojection error above params.outlierThresholdPx
  int pointsRefined = 0;
  int viewsRefined = 0;
  int viewsHeld = 0;  // non-anchored references not determined by the gauge rule
  // RMS reprojection error (pixels) over the inlier observations (the final outliers excluded),
  // before and after.
  double initialRmsPx = 0.0, finalRmsPx = 0.0;
  int iterations = 0;
  bool converged = false;     // Ceres reports convergence (not the iteration cap or a failure)
  std::string solverMessage;  // Ceres' termination message
  std::vector<ViewAdjustment> views;  // one per map view
};

class ReferenceBundleAdjuster {
 public:
  // Throws reftrack::Error naming a bad field of params.
  explicit ReferenceBundleAdjuster(BundleAdjustmentParams params = {});

  // Refines map.views[i].T of the determined non-anchored references and map.points[*].world in
  // place; the anchored references are not touched. Throws reftrack::Error when an observation
  // names a view or corner that does not exist.
  BundleAdjustmentReport adjust(MultiReferenceMap& map) const;

  const BundleAdjustmentParams& params() const { return params_; }

 private:
  BundleAdjustmentParams params_;
};

}  // namespace reftrack
