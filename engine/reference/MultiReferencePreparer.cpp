#include "engine/reference/MultiReferencePreparer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <map>
#include <numbers>
#include <numeric>
#include <sstream>

#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/reference/MultiViewTriangulator.hpp"
#include "engine/relocalisation/ReferenceKeypointBuilder.hpp"

namespace reftrack {

namespace {

// Disjoint sets over (reference, corner) nodes, path halving + union by size. Hand-written:
// neither OpenCV (cv::partition is quadratic in the node count) nor Eigen has one.
class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n), size_(n, 1) {
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  std::size_t find(std::size_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }

 private:
  std::vector<std::size_t> parent_, size_;
};

double viewAngleDeg(const RigidPose& a, const RigidPose& b) {
  const Eigen::Vector3d za = a.rotation().row(2).transpose(), zb = b.rotation().row(2).transpose();
  return std::acos(std::clamp(za.dot(zb), -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

// One kept pairwise match: its two nodes, its Eq. 9/10 point in the world frame and the
// correlation peak in B it was triangulated from (with A's corner).
struct PairMatch {
  std::size_t nodeA, nodeB;
  Eigen::Vector3d world;
  cv::Point2f peakB;
};

}  // namespace

MultiReferencePreparer::MultiReferencePreparer(PinholeCamera camera, Params params)
    : camera_(std::move(camera)), params_(std::move(params)) {
  camera_.check();
  params_.check();
}

std::string MultiReferencePreparer::viewFileName(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "reference_%02d.png", index);
  return name;
}

void MultiReferencePreparer::checkImages(const std::vector<ReferenceImage>& images) const {
  if (images.size() < 2)
    throw Error("at least 2 reference images are needed, got " + std::to_string(images.size()));
  for (const ReferenceImage& r : images) checkReferenceImage(r, camera_);
  for (std::size_t a = 0; a < images.size(); ++a)
    for (std::size_t b = a + 1; b < images.size(); ++b)
      checkDistinctReferenceImages(images[a], images[b]);
}

MultiPreparation MultiReferencePreparer::prepare(const std::vector<ReferenceImage>& images,
                                                 const MarkerSpec& marker,
                                                 const PairProgress& progress) const {
  checkImages(images);
  const MarkerPoseEstimator estimator(marker, camera_, params_.marker);
  std::vector<MeasuredPose> poses;
  for (const ReferenceImage& r : images) {
    const MarkerPose pose = estimator.estimate(r.image, r.name);
    poses.push_back({pose.worldToCamera, pose.reprojectionRmsPx});
  }
  return prepare(images, poses, "marker " + marker.toString(), progress);
}

MultiPreparation MultiReferencePreparer::prepare(const std::vector<ReferenceImage>& images,
                                                 const std::vector<MeasuredPose>& measured,
                                                 const std::string& poseSource,
                                                 const PairProgress& progress) const {
  checkImages(images);
  if (measured.size() != images.size())
    throw Error(std::to_string(measured.size()) + " poses (" + poseSource + ") for " +
                std::to_string(images.size()) + " reference images: one per image is needed");
  MultiPreparationReport report;
  std::vector<RigidPose> poses;
  for (const MeasuredPose& m : measured) {
    poses.push_back(m.worldToCamera);
    report.markerRmsPx.push_back(m.reprojectionRmsPx);
  }
  return build(images, poses, poseSource, report, progress, false);
}

MultiPreparation MultiReferencePreparer::prepare(const std::vector<ReferenceImage>& images,
                                                 const std::vector<RigidPose>& poses,
                                                 const std::string& poseSource,
                                                 const PairProgress& progress) const {
  checkImages(images);
  if (poses.size() != images.size())
    throw Error(std::to_string(poses.size()) + " poses (" + poseSource + ") for " +
                std::to_string(images.size()) + " reference images: one per image is needed");
  MultiPreparationReport report;
  report.markerRmsPx.assign(images.size(), std::nullopt);
  return build(images, poses, poseSource, report, progress, true);
}

MultiPreparation MultiReferencePreparer::matchAndMerge(
    const std::vector<ReferenceImage>& images, const std::vector<RigidPose>& poses,
    const std::string& poseSource, MultiPreparationReport report, const PairProgress& progress,
    const CornerParams& cornerParams, bool denser) const {
  const int n = static_cast<int>(images.size());
  MultiPreparation out;
  MultiReferenceMap& map = out.map;
  map.camera = camera_;
  map.poseSource = poseSource;
  map.preparationParams = params_.toYaml();
  if (denser) map.denserCorners = cornerParams;
  report.denserCorners = denser;

  // Corners of every reference, found once (one detector, in order, as the two-view preparation
  // does for A then B).
  std::vector<cv::Mat> grays;
  std::vector<std::vector<cv::Point2f>> positions;
  std::vector<std::size_t> firstNode;
  std::size_t nodes = 0;
  const CornerDetector detector(cornerParams);
  for (int v = 0; v < n; ++v) {
    const ReferenceImage& r = images[static_cast<std::size_t>(v)];
    grays.push_back(toGray8(r.image));
    const std::vector<Corner> corners = detector.detect(grays.back());
    positions.push_back(positionsOf(corners));
    ReferenceView view;
    view.name = viewFileName(v);
    view.T = poses[static_cast<std::size_t>(v)];
    view.anchored = true;
    view.image = r.image;
    view.corners = referenceCornersOf(corners);
    map.views.push_back(std::move(view));
    report.corners.push_back(static_cast<int>(corners.size()));
    firstNode.push_back(nodes);
    nodes += corners.size();
  }

  // Every pair through the two-view matcher (paper Sec. 3.3).
  std::vector<PairMatch> pairMatches;
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      const RigidPose &Ta = poses[static_cast<std::size_t>(a)],
                      &Tb = poses[static_cast<std::size_t>(b)];
      ReferencePairReport pair;
      pair.a = a;
      pair.b = b;
      pair.denserCorners = denser;
      pair.baselineMetres = (Ta.cameraCentre() - Tb.cameraCentre()).norm();
      pair.viewAngleDeg = viewAngleDeg(Ta, Tb);
      std::ostringstream why;
      if (pair.baselineMetres < params_.minBaselineMetres)
        why << "baseline " << pair.baselineMetres * 1000.0 << " mm < preparation.min_baseline_m "
            << params_.minBaselineMetres * 1000.0 << " mm";
      else if (pair.viewAngleDeg > params_.maxPairViewAngleDeg)
        why << "view angle " << pair.viewAngleDeg << " deg > preparation.max_pair_view_angle_deg "
            << params_.maxPairViewAngleDeg;
      pair.skipped = why.str();
      if (pair.skipped.empty()) {
        const EpipolarGuidedMatcher matcher(camera_, Ta, Tb, params_.matching);
        const EpipolarMatchResult matched = matcher.match(
            grays[static_cast<std::size_t>(a)], positions[static_cast<std::size_t>(a)],
            grays[static_cast<std::size_t>(b)], positions[static_cast<std::size_t>(b)]);
        pair.matched = true;
        pair.matching = matched.stats;
        pair.merged = static_cast<int>(matched.matches.size()) >= params_.minPairMatches;
        if (pair.merged) {
          const RigidPose AtoWorld = Ta.inverse();
          for (const ReferenceMatch& m : matched.matches)
            pairMatches.push_back(
                {firstNode[static_cast<std::size_t>(a)] + static_cast<std::size_t>(m.cornerA),
                 firstNode[static_cast<std::size_t>(b)] + static_cast<std::size_t>(m.cornerB),
                 AtoWorld * m.pointA,
                 m.peakB.value_or(
                     positions[static_cast<std::size_t>(b)][static_cast<std::size_t>(m.cornerB)])});
        }
      }
      if (progress) progress(pair);
      report.pairs.push_back(pair);
    }
  }

  // Tracks: connected (reference, corner) nodes.
  UnionFind sets(nodes);
  for (const PairMatch& m : pairMatches) sets.unite(m.nodeA, m.nodeB);
  std::map<std::size_t, std::vector<std::size_t>> trackMatches;  // root -> indices of pairMatches
  for (std::size_t i = 0; i < pairMatches.size(); ++i)
    trackMatches[sets.find(pairMatches[i].nodeA)].push_back(i);
  const auto nodeOf = [&](std::size_t node) {
    const auto it = std::upper_bound(firstNode.begin(), firstNode.end(), node);
    const int view = static_cast<int>(it - firstNode.begin()) - 1;
    return PointObservation{view,
                            static_cast<int>(node - firstNode[static_cast<std::size_t>(view)])};
  };
  std::vector<cv::Point2f> undistorted;
  {
    std::vector<cv::Point2f> all;
    for (const auto& p : positions) all.insert(all.end(), p.begin(), p.end());
    undistorted = camera_.undistortPixels(all);
  }
  const MultiViewTriangulator triangulator(camera_.K());
  const auto posedPixel = [&](std::size_t node) {
    const PointObservation o = nodeOf(node);
    const cv::Point2f& p = undistorted[node];
    return PosedPixel{poses[static_cast<std::size_t>(o.view)], Eigen::Vector2d(p.x, p.y)};
  };
  double multiViewSq = 0.0;
  int multiViewCount = 0;
  report.tracks = static_cast<int>(trackMatches.size());
  for (const auto& [root, matchIndices] : trackMatches) {
    std::vector<std::size_t> trackNodes;
    for (std::size_t i : matchIndices)
      for (std::size_t node : {pairMatches[i].nodeA, pairMatches[i].nodeB})
        if (std::find(trackNodes.begin(), trackNodes.end(), node) == trackNodes.end())
          trackNodes.push_back(node);
    std::sort(trackNodes.begin(), trackNodes.end());
    bool consistent = true;
    for (std::size_t k = 1; k < trackNodes.size(); ++k)
      consistent = consistent && nodeOf(trackNodes[k]).view != nodeOf(trackNodes[k - 1]).view;
    if (!consistent) {
      ++report.inconsistentTracks;
      continue;
    }
    MapPoint point;
    // The pixel each observation was measured at (PointObservation::peak), per track node.
    std::vector<std::optional<cv::Point2f>> peaks(trackNodes.size());
    if (trackNodes.size() == 2) {
      // Two references: the pair's own Eq. 9/10 point, as the two-view preparation keeps it,
      // measured at A's corner and the correlation peak in B.
      const PairMatch& m = pairMatches[matchIndices.front()];
      point.world = m.world;
      peaks[trackNodes[0] == m.nodeB ? 0 : 1] = m.peakB;
    } else {
      // 3+ references: all measurements at once, the worst observation out while any is off.
      // The measurements are those the pairwise triangulations used: the corner of the track's
      // first reference (the anchor: the A side of each of its pairs) and, in every reference
      // matched with the anchor, the projection of that pair's point, i.e. the sub-pixel
      // correlation peak of the anchor's window (that reference's own corner may lie up to
      // matching.max_peak_offset_px away from it). A reference not matched with the anchor
      // contributes its corner. (Simulated desk scene, 3 references, depth against the true
      // surface in the first: from the corners only, 4.0 mm RMS over all its points; from these
      // measurements 2.9 mm, and 2.9 mm for the points seen by all three.)
      std::vector<PosedPixel> measured;
      for (std::size_t node : trackNodes) measured.push_back(posedPixel(node));
      for (std::size_t i : matchIndices) {
        if (pairMatches[i].nodeA != trackNodes.front()) continue;
        const std::size_t k = static_cast<std::size_t>(
            std::find(trackNodes.begin(), trackNodes.end(), pairMatches[i].nodeB) -
            trackNodes.begin());
        const Eigen::Vector3d q = camera_.K() * (measured[k].worldToCamera * pairMatches[i].world);
        if (q.z() > 0.0) measured[k].pixel = q.head<2>() / q.z();
        peaks[k] = pairMatches[i].peakB;
      }
      Eigen::Vector3d start = Eigen::Vector3d::Zero();
      for (std::size_t i : matchIndices) start += pairMatches[i].world;
      start /= static_cast<double>(matchIndices.size());
      for (;;) {
        const Eigen::Vector3d linear = triangulator.linear(measured);
        point.world = triangulator.refine(measured, linear.allFinite() ? linear : start);
        std::size_t worst = 0;
        double worstError = -1.0;
        for (std::size_t k = 0; k < measured.size(); ++k) {
          const double e = triangulator.reprojectionError(measured[k], point.world);
          if (e > worstError) {
            worstError = e;
            worst = k;
          }
        }
        if (worstError <= params_.maxTrackReprojectionErrorPx) break;
        trackNodes.erase(trackNodes.begin() + static_cast<std::ptrdiff_t>(worst));
        measured.erase(measured.begin() + static_cast<std::ptrdiff_t>(worst));
        peaks.erase(peaks.begin() + static_cast<std::ptrdiff_t>(worst));
        ++report.droppedObservations;
        if (trackNodes.size() < 2) break;
      }
      if (trackNodes.size() < 2 || !point.world.allFinite()) {
        ++report.droppedPoints;
        continue;
      }
      for (const PosedPixel& m : measured) {
        const double e = triangulator.reprojectionError(m, point.world);
        multiViewSq += e * e;
        ++multiViewCount;
      }
    }
    bool inFront = true;
    for (std::size_t k = 0; k < trackNodes.size(); ++k) {
      PointObservation o = nodeOf(trackNodes[k]);
      o.peak = peaks[k];
      point.observations.push_back(o);
      inFront =
          inFront &&
          (poses[static_cast<std::size_t>(point.observations.back().view)] * point.world).z() > 0.0;
    }
    if (!inFront) {
      ++report.droppedPoints;
      continue;
    }
    map.points.push_back(std::move(point));
  }
  report.multiViewRmsPx = multiViewCount > 0 ? std::sqrt(multiViewSq / multiViewCount) : 0.0;
  report.observationHistogram.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const MapPoint& p : map.points) ++report.observationHistogram[p.observations.size()];

  out.report = std::move(report);
  return out;
}

MultiPreparation MultiReferencePreparer::build(const std::vector<ReferenceImage>& images,
                                               const std::vector<RigidPose>& poses,
                                               const std::string& poseSource,
                                               MultiPreparationReport report,
                                               const PairProgress& progress,
                                               bool posesGiven) const {
  const int n = static_cast<int>(images.size());
  for (int v = 0; v < n; ++v)
    if (!poses[static_cast<std::size_t>(v)].allFinite())
      throw Error("the pose of reference image '" + images[static_cast<std::size_t>(v)].name +
                  "' (" + poseSource + ") is not finite");

  // The references' own corners first; a map short of preparation.target_points whose corners
  // repeat poorly (soft images repeat few of the strongest Harris corners between views) is made
  // again from denser corners, and the map with more points is kept.
  MultiPreparation out =
      matchAndMerge(images, poses, poseSource, report, progress, params_.corners, false);
  // The best pair's repeated corners over the fewer corners of its images: its kept matches and
  // those dropped for too little parallax, which repeat but lie too close to the references'
  // common line of sight. Counting only the kept ones took two ViSP frames 15 mm and 1.3 degrees
  // apart (40/80: 3 kept, 273 dropped for parallax) to denser corners and a 34-point map on which
  // 17 frames were tracked 5-28 px off; the pair is now refused, naming the parallax.
  double repeat = 0.0;
  for (const ReferencePairReport& pr : out.report.pairs)
    if (pr.matched && std::min(pr.matching.cornersA, pr.matching.cornersB) > 0)
      repeat =
          std::max(repeat, static_cast<double>(pr.matching.kept + pr.matching.droppedLowParallax) /
                               std::min(pr.matching.cornersA, pr.matching.cornersB));
  out.report.cornerRepeat = repeat;
  if (static_cast<int>(out.map.points.size()) < params_.targetPoints &&
      repeat <= params_.denserCornerMaxRepeat) {
    MultiPreparation denser =
        matchAndMerge(images, poses, poseSource, report, progress, params_.denserCorners(), true);
    denser.report.pointsBeforeDenserCorners = static_cast<int>(out.map.points.size());
    if (denser.map.points.size() > out.map.points.size()) {
      out = std::move(denser);
    } else {
      out.report.pointsBeforeDenserCorners = static_cast<int>(out.map.points.size());
      out.report.denserCornersGave = static_cast<int>(denser.map.points.size());
    }
  }
  MultiReferenceMap& map = out.map;
  report = std::move(out.report);
  if (static_cast<int>(map.points.size()) < params_.minMatches) {
    std::ostringstream ss;
    ss << "only " << map.points.size() << " map points from " << n << " reference images (at least "
       << params_.minMatches << " needed):";
    for (const ReferencePairReport& p : report.pairs) {
      ss << " '" << images[static_cast<std::size_t>(p.a)].name << "'-'"
         << images[static_cast<std::size_t>(p.b)].name << "' ";
      if (!p.matched)
        ss << "skipped (" << p.skipped << ");";
      else
        ss << p.matching.kept << " matches of " << p.matching.cornersA << "/" << p.matching.cornersB
           << " corners;";
      if (p.matched && p.matching.droppedLowParallax > p.matching.kept)
        ss << " " << p.matching.droppedLowParallax
           << " more dropped for too little parallax (matching.min_parallax_deg): the two are "
           << std::lround(p.baselineMetres * 1000.0) << " mm and " << std::setprecision(2)
           << p.viewAngleDeg << " degrees apart, take references farther apart;";
    }
    ss << " do the images overlap, and are the poses (" << poseSource << ") right?";
    throw Error(ss.str());
  }
  if (params_.refines(posesGiven))
    report.poseRefinement = refineReferencePoses(map, params_.poseRefinement);
  if (params_.relocalisation.enabled) buildReferenceKeypoints(map, params_.relocalisation);
  map.check();
  out.report = std::move(report);
  return out;
}

}  // namespace reftrack
