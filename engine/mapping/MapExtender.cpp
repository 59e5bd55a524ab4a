#include "engine/mapping/MapExtender.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/reference/EpipolarGuidedMatcher.hpp"
#include "engine/reference/MultiReferencePreparer.hpp"

namespace reftrack {

namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

Eigen::Vector3d opticalAxis(const RigidPose& worldToCamera) {
  return worldToCamera.rotation().row(2).transpose();  // camera z in world coordinates
}

std::vector<cv::Point2f> pixelsOf(const std::vector<ReferenceCorner>& corners) {
  std::vector<cv::Point2f> out;
  out.reserve(corners.size());
  for (const ReferenceCorner& c : corners) out.push_back(c.pixel);
  return out;
}

std::string unusedViewName(const MultiReferenceMap& map) {
  for (int i = map.size();; ++i) {
    const std::string name = MultiReferencePreparer::viewFileName(i);
    const bool used = std::any_of(map.views.begin(), map.views.end(),
                                  [&](const ReferenceView& v) { return v.name == name; });
    if (!used) return name;
  }
}

int observationIn(const MapPoint& p, int view) {
  for (const PointObservation& o : p.observations)
    if (o.view == view) return o.corner;
  return -1;
}

}  // namespace

const char* toString(ExtensionReason reason) {
  return reason == ExtensionReason::Distance ? "distance" : "angle";
}

void MapExtenderParams::check() const {
  tracker.check();
  preparation.check();
  extension.check();
  bundleAdjustment.check();
}

MapExtender::MapExtender(MultiReferenceMap map, MapExtenderParams params)
    : map_(std::move(map)), params_(std::move(params)), adjuster_(params_.bundleAdjustment) {
  params_.check();
  if (map_.size() < 2)
    throw Error("the map holds " + std::to_string(map_.size()) +
                " reference(s); extending needs at least two");
  pointsBefore_ = static_cast<int>(map_.points.size());
  // Start on reference 0 and the reference sharing most points with it.
  int partner = 1;
  for (int v = 1; v < map_.size(); ++v)
    if (map_.sharedPoints(0, v) > map_.sharedPoints(0, partner)) partner = v;
  if (map_.sharedPoints(0, partner) < params_.extension.minNewPoints)
    throw Error("reference 0 shares " + std::to_string(map_.sharedPoints(0, partner)) +
                " map points with any other reference; the tracker needs at least " +
                std::to_string(params_.extension.minNewPoints));
  startTracker(0, partner);
}

MapExtender::~MapExtender() = default;

void MapExtender::startTracker(int a, int b) {
  tracker_ = std::make_unique<PoseTracker>(map_.pair(a, b), params_.tracker);
  pairA_ = a;
  pairB_ = b;
}

MapExtender::Coverage MapExtender::coverage(const RigidPose& pose) const {
  Coverage c;
  const Eigen::Vector3d centre = pose.cameraCentre(), axis = opticalAxis(pose);
  double nearest = INFINITY, bestAngle = INFINITY;
  for (int v = 0; v < map_.size(); ++v) {
    const RigidPose& T = map_.views[static_cast<std::size_t>(v)].T;
    const double d = (T.cameraCentre() - centre).norm();
    if (d < nearest) {
      nearest = d;
      c.nearestView = v;
    }
    if (d > params_.extension.maxDistanceMetres) continue;
    const double angle = std::acos(std::clamp(opticalAxis(T).dot(axis), -1.0, 1.0)) * kRadToDeg;
    bestAngle = std::min(bestAngle, angle);
  }
  c.distanceMetres = nearest;
  if (std::isinf(bestAngle)) {
    c.covered = false;
    c.reason = ExtensionReason::Distance;
    return c;
  }
  c.angleDeg = bestAngle;
  c.covered = bestAngle <= params_.extension.maxAngleDeg;
  c.reason = ExtensionReason::Angle;
  return c;
}

ExtensionFrame MapExtender::process(const cv::Mat& frame, int frameIndex) {
  ExtensionFrame out;
  out.pairA = pairA_;
  out.pairB = pairB_;
  out.tracking = tracker_->process(frame);
  const PoseTrackingResult& r = out.tracking;
  const MapExtensionParams& e = params_.extension;
  out.wellSupported = r.worldToCamera.has_value() && r.state != TrackingState::Lost &&
                      r.inliers >= e.minInliers &&
                      r.supportSdPx <= e.maxSupportSdPx * resolutionScale(frame.size());
  if (!out.wellSupported) return out;
  const Coverage c = coverage(*r.worldToCamera);
  out.covered = c.covered;
  if (c.covered) return out;
  if (map_.size() >= e.maxReferences) {
    out.rejected = "the map already holds " + std::to_string(map_.size()) +
                   " references (extension.max_references)";
    return out;
  }
  out.rejected = addReference(frame, frameIndex, *r.worldToCamera, c);
  out.added = out.rejected.empty();
  return out;
}

std::string MapExtender::addReference(const cv::Mat& frame, int frameIndex, const RigidPose& pose,
                                      const Coverage& coverage) {
  const MapExtensionParams& e = params_.extension;
  const PinholeCamera& camera = map_.camera;
  const cv::Mat gray = toGray8(frame);
  const std::vector<Corner> detected = CornerDetector(params_.preparation.corners).detect(gray);

  MultiReferenceMap m = map_;  // committed only when the reference is kept
  const int n = m.size();
  ReferenceView view;
  view.name = unusedViewName(m);
  view.T = pose;
  view.anchored = false;
  view.image = frame.clone();
  view.corners = referenceCornersOf(detected);
  m.views.push_back(view);
  const std::vector<cv::Point2f> newPixels = pixelsOf(view.corners);

  // The existing references it overlaps: most map points inside its view first.
  std::vector<int> overlap(static_cast<std::size_t>(n), 0);
  const cv::Size size = camera.imageSize();
  for (const MapPoint& p : m.points) {
    const Eigen::Vector3d Xc = pose * p.world;
    if (!(Xc.z() > 0.0)) continue;
    const Eigen::Vector2d px = camera.projectDistorted(Xc);
    if (px.x() < 0 || px.y() < 0 || px.x() > size.width - 1 || px.y() > size.height - 1) continue;
    for (const PointObservation& o : p.observations) ++overlap[static_cast<std::size_t>(o.view)];
  }
  std::vector<int> candidates;
  for (int v = 0; v < n; ++v) {
    const RigidPose& T = m.views[static_cast<std::size_t>(v)].T;
    const double baseline = (T.cameraCentre() - pose.cameraCentre()).norm();
    const double viewAngleDeg =
        std::acos(std::clamp(opticalAxis(T).dot(opticalAxis(pose)), -1.0, 1.0)) * kRadToDeg;
    // The preparation's pair gates: enough baseline, view change the warped NCC can follow.
    if (overlap[static_cast<std::size_t>(v)] >= std::max(1, e.minOverlapPoints) &&
        baseline >= params_.preparation.minBaselineMetres &&
        viewAngleDeg <= params_.preparation.maxPairViewAngleDeg)
      candidates.push_back(v);
  }
  std::stable_sort(candidates.begin(), candidates.end(), [&](int a, int b) {
    return overlap[static_cast<std::size_t>(a)] > overlap[static_cast<std::size_t>(b)];
  });
  if (static_cast<int>(candidates.size()) > e.matchReferences)
    candidates.resize(static_cast<std::size_t>(e.matchReferences));
  if (candidates.empty())
    return "no reference overlaps it with " + std::to_string(e.minOverlapPoints) +
           " map points, enough baseline and a view angle within "
           "preparation.max_pair_view_angle_deg";

  // Which map point each existing corner belongs to.
  std::vector<std::vector<int>> pointOf(m.views.size());
  for (std::size_t v = 0; v < m.views.size(); ++v) pointOf[v].assign(m.views[v].corners.size(), -1);
  for (std::size_t i = 0; i < m.points.size(); ++i)
    for (const PointObservation& o : m.points[i].observations)
      pointOf[static_cast<std::size_t>(o.view)][static_cast<std::size_t>(o.corner)] =
          static_cast<int>(i);

  EpipolarMatcherParams matching = params_.preparation.matching;
  matching.maxEpipolarDistancePx = e.maxEpipolarDistancePx;
  matching.maxReprojectionErrorPx = e.maxReprojectionErrorPx;
  AddedReference added;
  added.view = n;
  added.frameIndex = frameIndex;
  added.reason = coverage.reason;
  added.nearestView = coverage.nearestView;
  added.distanceMetres = coverage.distanceMetres;
  added.angleDeg = coverage.angleDeg;
  auto& newPointOf = pointOf[static_cast<std::size_t>(n)];
  for (int j : candidates) {
    const ReferenceView& old = m.views[static_cast<std::size_t>(j)];
    const EpipolarGuidedMatcher matcher(camera, old.T, pose, matching);
    const EpipolarMatchResult result =
        matcher.match(toGray8(old.image), pixelsOf(old.corners), gray, newPixels);
    if (!result.matches.empty()) added.matchedViews.push_back(j);
    const RigidPose oldToWorld = old.T.inverse();
    for (const ReferenceMatch& match : result.matches) {
      int& oldPoint = pointOf[static_cast<std::size_t>(j)][static_cast<std::size_t>(match.cornerA)];
      int& newPoint = newPointOf[static_cast<std::size_t>(match.cornerB)];
      if (oldPoint >= 0 && newPoint >= 0) continue;  // both taken: the same point or a conflict
      if (oldPoint >= 0) {  // an existing point gains its corner in the new reference
        MapPoint& p = m.points[static_cast<std::size_t>(oldPoint)];
        if (observationIn(p, n) >= 0) continue;  // already has another corner there: conflict
        p.observations.push_back({n, match.cornerB, match.peakB});
        newPoint = oldPoint;
        ++added.pointsExtended;
      } else if (newPoint >= 0) {  // the new corner's point gains this old corner
        MapPoint& p = m.points[static_cast<std::size_t>(newPoint)];
        if (observationIn(p, j) >= 0) continue;
        p.observations.push_back({j, match.cornerA});
        oldPoint = newPoint;
      } else {  // a new point
        m.points.push_back({oldToWorld * match.pointA,
                            {{j, match.cornerA, match.peakA}, {n, match.cornerB, match.peakB}}});
        oldPoint = newPoint = static_cast<int>(m.points.size()) - 1;
        ++added.pointsAdded;
      }
    }
  }
  if (added.pointsExtended + added.pointsAdded < e.minNewPoints)
    return "its corners matched " + std::to_string(added.pointsExtended + added.pointsAdded) +
           " map points (at least " + std::to_string(e.minNewPoints) + " needed)";

  added.adjustment = adjuster_.adjust(m);
  int partner = -1;
  for (int v = 0; v < n; ++v)
    if (partner < 0 || m.sharedPoints(n, v) > m.sharedPoints(n, partner)) partner = v;
  added.trackerPartner = partner;
  map_ = std::move(m);
  added_.push_back(added);
  startTracker(n, partner);
  return {};
}

std::string MapExtender::add(const cv::Mat& frame, int frameIndex, const RigidPose& worldToCamera) {
  if (frame.empty() || frame.size() != map_.camera.imageSize())
    throw Error("the frame to add is " + std::to_string(frame.cols) + "x" +
                std::to_string(frame.rows) + " but the map's camera is for " +
                std::to_string(map_.camera.imageSize().width) + "x" +
                std::to_string(map_.camera.imageSize().height) + " images");
  if (map_.size() >= params_.extension.maxReferences)
    return "the map already holds " + std::to_string(map_.size()) +
           " references (extension.max_references)";
  return addReference(frame, frameIndex, worldToCamera, coverage(worldToCamera));
}

BundleAdjustmentReport MapExtender::finish() { return adjuster_.adjust(map_); }

}  // namespace reftrack
