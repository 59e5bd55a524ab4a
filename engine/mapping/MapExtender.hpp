#pragma once
// MapExtender (issue 13, `reftrack extend`): grows a MultiReferenceMap from a video. Each frame is
// tracked in 6-DOF (the paper's PoseTracker on a pair of the map's references, starting with the
// pair (0, 1), so the first frame must be near reference 0 or 1). A well-supported frame (tracked,
// enough inliers, small support SD) that lies outside the covered volume (no reference within
// maxDistanceMetres whose optical axis is within maxAngleDeg of the frame's) becomes a new
// reference, anchored = false, at its tracked pose: its corners (the preparation's detector) are
// matched epipolar-guided to the existing references it overlaps most; each match extends the map
// point of the old corner or creates a new point triangulated by the matcher. The bundle
// adjustment (ReferenceBundleAdjuster) then refines the added references and the points, and the
// tracker carries on from the new reference: a PoseTracker on the pair (new, the reference sharing
// most points with it), which the very next frame initialises against, as it is next to it.
// finish() runs a last bundle adjustment over the whole map.
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "engine/config/BundleAdjustmentParams.hpp"
#include "engine/config/MapExtensionParams.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "engine/reference/ReferenceBundleAdjuster.hpp"
#include "engine/reference/ReferencePreparer.hpp"
#include "engine/tracking/PoseTracker.hpp"

namespace reftrack {

struct MapExtenderParams {
  TrackerParams tracker;                // the 6-DOF tracker's
  ReferencePreparerParams preparation;  // corner detector and matcher of new references
  MapExtensionParams extension;         // when to add, how to match
  BundleAdjustmentParams bundleAdjustment;
  void check() const;  // throws reftrack::Error naming the bad field
};

// Why a frame was (or would have been) added: it is too far from every reference, or near some
// but seen from a direction none of the near ones covers.
enum class ExtensionReason { Distance, Angle };
const char* toString(ExtensionReason reason);

struct AddedReference {
  int view = -1;        // index in the map
  int frameIndex = -1;  // the video frame it was taken from
  ExtensionReason reason = ExtensionReason::Distance;
  int nearestView = -1;           // the reference nearest to the frame's camera centre
  double distanceMetres = 0.0;    // ... and its distance
  double angleDeg = 0.0;          // smallest optical-axis angle to a reference within the distance
  std::vector<int> matchedViews;  // existing references its corners were matched to
  int pointsExtended = 0;         // existing map points that gained an observation in it
  int pointsAdded = 0;            // new map points (seen by it and one existing reference)
  int trackerPartner = -1;        // the tracker continued on the pair (view, trackerPartner)
  BundleAdjustmentReport adjustment;  // the adjustment run right after adding it
};

struct ExtensionFrame {
  PoseTrackingResult tracking;
  int pairA = -1, pairB = -1;  // the references the tracker used on this frame
  bool wellSupported = false;
  bool covered = true;   // false: outside the covered volume (only judged when well supported)
  bool added = false;    // this frame became reference added.back()
  std::string rejected;  // uncovered but not added, and why (too few matches, reference cap)
};

class MapExtender {
 public:
  // Throws reftrack::Error on bad params or a map without two references sharing points.
  MapExtender(MultiReferenceMap map, MapExtenderParams params);
  ~MapExtender();

  // One video frame (BGR or grey, the map's image size).
  ExtensionFrame process(const cv::Mat& frame, int frameIndex);
  // Adds `frame` (the map's image size) as a new reference at `worldToCamera` now, whether or not
  // the coverage test asks for it (the viewer's "Add to map"): the same matching and bundle
  // adjustment as process() (anchored references fixed: the world frame stays); the tracker
  // carries on from it. Returns an empty string, or why it was not added (the map unchanged).
  std::string add(const cv::Mat& frame, int frameIndex, const RigidPose& worldToCamera);
  // The closing bundle adjustment over every reference; returns its report.
  BundleAdjustmentReport finish();

  const MultiReferenceMap& map() const { return map_; }
  MultiReferenceMap& map() { return map_; }
  const std::vector<AddedReference>& added() const { return added_; }
  int pointsBefore() const { return pointsBefore_; }

 private:
  struct Coverage {
    bool covered = true;
    ExtensionReason reason = ExtensionReason::Distance;
    int nearestView = -1;
    double distanceMetres = 0.0, angleDeg = 0.0;
  };
  Coverage coverage(const RigidPose& worldToCamera) const;
  // Adds the frame as a reference; returns an empty string, or why it was not added.
  std::string addReference(const cv::Mat& frame, int frameIndex, const RigidPose& pose,
                           const Coverage& coverage);
  void startTracker(int a, int b);

  MultiReferenceMap map_;
  MapExtenderParams params_;
  ReferenceBundleAdjuster adjuster_;
  std::unique_ptr<PoseTracker> tracker_;
  int pairA_ = -1, pairB_ = -1;
  std::vector<AddedReference> added_;
  int pointsBefore_ = 0;
};

}  // namespace reftrack
