#include "engine/reference/ReferencePreparer.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"

namespace reftrack {

namespace {

constexpr int kGridColumns = 4, kGridRows = 3;

std::string sizeText(cv::Size s) {
  return std::to_string(s.width) + "x" + std::to_string(s.height);
}

int occupiedCells(const std::vector<ReferenceMatch>& matches,
                  const std::vector<ReferenceCorner>& cornersA, cv::Size size) {
  std::vector<char> cells(kGridColumns * kGridRows, 0);
  for (const ReferenceMatch& m : matches) {
    const cv::Point2f p = cornersA[static_cast<size_t>(m.cornerA)].pixel;
    const int cx =
        std::clamp(static_cast<int>(p.x * kGridColumns / size.width), 0, kGridColumns - 1);
    const int cy = std::clamp(static_cast<int>(p.y * kGridRows / size.height), 0, kGridRows - 1);
    cells[static_cast<size_t>(cy * kGridColumns + cx)] = 1;
  }
  int n = 0;
  for (char c : cells) n += c;
  return n;
}

}  // namespace

std::vector<ReferenceCorner> referenceCornersOf(const std::vector<Corner>& corners) {
  std::vector<ReferenceCorner> out;
  out.reserve(corners.size());
  for (const Corner& c : corners) out.push_back({c.position, c.contrast});
  return out;
}

void checkReferenceImage(const ReferenceImage& r, const PinholeCamera& camera) {
  if (r.image.empty()) throw Error("reference image '" + r.name + "' is empty or unreadable");
  if (r.image.size() != camera.imageSize())
    throw Error("reference image '" + r.name + "' is " + sizeText(r.image.size()) +
                " but the camera is calibrated for " + sizeText(camera.imageSize()) +
                " (wrong camera file?)");
}

void checkDistinctReferenceImages(const ReferenceImage& a, const ReferenceImage& b) {
  if (a.image.type() == b.image.type() && a.image.size() == b.image.size() &&
      cv::norm(a.image, b.image, cv::NORM_INF) == 0.0)
    throw Error("reference images '" + a.name + "' and '" + b.name +
                "' are identical: two views from different places are needed (no baseline)");
}

void ReferencePreparerParams::check() const {
  corners.check();
  matching.check();
  marker.check();
  requireFiniteInRange("preparation.min_baseline_m", minBaselineMetres, 0.0, 1e6);
  requireIntInRange("preparation.min_matches", minMatches, 0, 10000000);
  requireFiniteInRange("preparation.max_pair_view_angle_deg", maxPairViewAngleDeg, 0.0, 180.0);
  requireIntInRange("preparation.min_pair_matches", minPairMatches, 1, 10000000);
  poseRefinement.check();
  requireFiniteInRange("preparation.max_track_reprojection_error_px", maxTrackReprojectionErrorPx,
                       1e-3, 1e3);
  requireIntInRange("preparation.target_points", targetPoints, 0, 10000000);
  requireFiniteInRange("preparation.denser_corner_max_repeat", denserCornerMaxRepeat, 0.0, 1.0);
  requireIntInRange("preparation.denser_corner_count", denserCornerCount, 1, 1000000);
  requireFiniteInRange("preparation.denser_corner_quality", denserCornerQuality, 1e-9, 1.0);
  requireFiniteInRange("preparation.denser_corner_min_distance_px", denserCornerMinDistancePx, 0.0,
                       1000.0);
  denserCorners().check();
  relocalisation.check();
}

void ReferencePreparerParams::write(cv::FileStorage& fs) const {
  fs << "corners"
     << "{";
  corners.write(fs);
  fs << "}"
     << "matching"
     << "{";
  matching.write(fs);
  fs << "}"
     << "marker"
     << "{"
     << "ambiguity_ratio" << marker.ambiguityRatio << "max_reprojection_rms_px"
     << marker.maxReprojectionRmsPx << "}"
     << "preparation"
     << "{"
     << "min_baseline_m" << minBaselineMetres << "min_matches" << minMatches
     << "max_pair_view_angle_deg" << maxPairViewAngleDeg << "min_pair_matches" << minPairMatches
     << "max_track_reprojection_error_px" << maxTrackReprojectionErrorPx << "target_points"
     << targetPoints << "denser_corner_max_repeat" << denserCornerMaxRepeat << "denser_corner_count"
     << denserCornerCount << "denser_corner_quality" << denserCornerQuality
     << "denser_corner_min_distance_px" << denserCornerMinDistancePx << "refine_poses"
     << (refinePoses ? "true" : "false") << "refine_given_poses"
     << (refineGivenPoses ? "true" : "false") << "pose_prior_origin_sd_px"
     << poseRefinement.originSdPx << "pose_prior_translation_sd_m"
     << poseRefinement.translationSdMetres << "pose_prior_rotation_sd_deg"
     << poseRefinement.rotationSdDeg << "pose_refinement_corner_sd_px" << poseRefinement.cornerSdPx
     << "pose_refinement_iterations" << poseRefinement.maxIterations << "}"
     << "relocalisation"
     << "{";
  relocalisation.write(fs);
  fs << "}";
}

void ReferencePreparerParams::read(const YamlNode& root,
                                   const std::vector<std::string>& otherSections) {
  if (root.isNull()) return;  // an empty file: the defaults
  if (!root.isMap()) root.fail("preparation parameters must be a map of sections");
  requireKeysWrittenBy(
      root, [](cv::FileStorage& fs) { ReferencePreparerParams{}.write(fs); }, otherSections);
  corners.read(root["corners"]);
  matching.read(root["matching"]);
  readConfigValue(root["marker"], "ambiguity_ratio", marker.ambiguityRatio);
  readConfigValue(root["marker"], "max_reprojection_rms_px", marker.maxReprojectionRmsPx);
  readConfigValue(root["preparation"], "min_baseline_m", minBaselineMetres);
  readConfigValue(root["preparation"], "min_matches", minMatches);
  readConfigValue(root["preparation"], "max_pair_view_angle_deg", maxPairViewAngleDeg);
  readConfigValue(root["preparation"], "min_pair_matches", minPairMatches);
  readConfigValue(root["preparation"], "max_track_reprojection_error_px",
                  maxTrackReprojectionErrorPx);
  readConfigValue(root["preparation"], "target_points", targetPoints);
  readConfigValue(root["preparation"], "denser_corner_max_repeat", denserCornerMaxRepeat);
  readConfigValue(root["preparation"], "denser_corner_count", denserCornerCount);
  readConfigValue(root["preparation"], "denser_corner_quality", denserCornerQuality);
  readConfigValue(root["preparation"], "denser_corner_min_distance_px", denserCornerMinDistancePx);
  readConfigValue(root["preparation"], "refine_poses", refinePoses);
  readConfigValue(root["preparation"], "refine_given_poses", refineGivenPoses);
  readConfigValue(root["preparation"], "pose_prior_origin_sd_px", poseRefinement.originSdPx);
  readConfigValue(root["preparation"], "pose_prior_translation_sd_m",
                  poseRefinement.translationSdMetres);
  readConfigValue(root["preparation"], "pose_prior_rotation_sd_deg", poseRefinement.rotationSdDeg);
  readConfigValue(root["preparation"], "pose_refinement_corner_sd_px", poseRefinement.cornerSdPx);
  readConfigValue(root["preparation"], "pose_refinement_iterations", poseRefinement.maxIterations);
  relocalisation.read(root["relocalisation"]);
  checkWithLines(root, [&] { check(); });
}

std::string ReferencePreparerParams::toYaml() const {
  cv::FileStorage fs(
      ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  write(fs);
  return fs.releaseAndGetString();
}

ReferencePreparerParams ReferencePreparerParams::load(const std::filesystem::path& file) {
  ReferencePreparerParams p;
  readParameterFile(file, [&](const YamlNode& root) { p.read(root); });
  return p;
}

ReferencePreparer::ReferencePreparer(PinholeCamera camera, Params params)
    : camera_(std::move(camera)), params_(std::move(params)) {
  camera_.check();
  params_.check();
}

void ReferencePreparer::checkImages(const ReferenceImage& a, const ReferenceImage& b) const {
  for (const ReferenceImage* r : {&a, &b}) checkReferenceImage(*r, camera_);
  checkDistinctReferenceImages(a, b);
}

Preparation ReferencePreparer::prepare(const ReferenceImage& a, const ReferenceImage& b,
                                       const MarkerSpec& marker) const {
  checkImages(a, b);
  const MarkerPoseEstimator estimator(marker, camera_, params_.marker);
  const MarkerPose poseA = estimator.estimate(a.image, a.name);
  const MarkerPose poseB = estimator.estimate(b.image, b.name);
  PreparationReport report;
  report.markerRmsA = poseA.reprojectionRmsPx;
  report.markerRmsB = poseB.reprojectionRmsPx;
  return triangulate(a, b, poseA.worldToCamera, poseB.worldToCamera, "marker " + marker.toString(),
                     report, false);
}

Preparation ReferencePreparer::prepare(const ReferenceImage& a, const ReferenceImage& b,
                                       const RigidPose& T_A, const RigidPose& T_B,
                                       const std::string& poseSource) const {
  checkImages(a, b);
  return triangulate(a, b, T_A, T_B, poseSource, PreparationReport{}, true);
}

Preparation ReferencePreparer::triangulate(const ReferenceImage& a, const ReferenceImage& b,
                                           const RigidPose& T_A, const RigidPose& T_B,
                                           const std::string& poseSource, PreparationReport report,
                                           bool posesGiven) const {
  if (!T_A.allFinite() || !T_B.allFinite())
    throw Error("the reference poses of '" + a.name + "' and '" + b.name + "' are not finite");
  report.baselineMetres = (T_A.cameraCentre() - T_B.cameraCentre()).norm();
  if (report.baselineMetres < params_.minBaselineMetres) {
    std::ostringstream ss;
    ss << "reference images '" << a.name << "' and '" << b.name << "' were taken "
       << report.baselineMetres * 1000.0 << " mm apart (" << poseSource << "); at least "
       << params_.minBaselineMetres * 1000.0
       << " mm of baseline is needed to triangulate: take B from another place";
    throw Error(ss.str());
  }

  const cv::Mat grayA = toGray8(a.image), grayB = toGray8(b.image);
  const CornerDetector detector(params_.corners);
  const std::vector<Corner> cornersA = detector.detect(grayA);
  const std::vector<Corner> cornersB = detector.detect(grayB);

  Preparation out;
  ReferenceMap& map = out.map;
  map.camera = camera_;
  map.T_A = T_A;
  map.T_B = T_B;
  map.imageA = a.image;
  map.imageB = b.image;
  map.cornersA = referenceCornersOf(cornersA);
  map.cornersB = referenceCornersOf(cornersB);
  map.poseSource = poseSource;
  map.preparationParams = params_.toYaml();

  const EpipolarGuidedMatcher matcher(camera_, T_A, T_B, params_.matching);
  EpipolarMatchResult matched =
      matcher.match(grayA, positionsOf(cornersA), grayB, positionsOf(cornersB));
  map.matches = std::move(matched.matches);
  report.matching = matched.stats;
  report.occupiedGridCells = occupiedCells(map.matches, map.cornersA, camera_.imageSize());

  if (static_cast<int>(map.matches.size()) < params_.minMatches) {
    const EpipolarMatchStats& s = report.matching;
    std::ostringstream ss;
    ss << "only " << s.kept << " A<->B matches survived (at least " << params_.minMatches
       << " needed): " << s.cornersA << " corners in '" << a.name << "', " << s.cornersB << " in '"
       << b.name << "', " << s.mutualMatches
       << " candidate matches; do the two images overlap, and are the poses (" << poseSource
       << ") right?";
    throw Error(ss.str());
  }
  if (params_.refines(posesGiven)) {
    // B's pose (A held) and the points from the matches, as the N-reference preparation does.
    MultiReferenceMap multi = MultiReferenceMap::fromPair(map);
    report.poseRefinement = refineReferencePoses(multi, params_.poseRefinement);
    ReferenceMap refined = multi.pair(0, 1);
    map.T_B = refined.T_B;
    map.matches = std::move(refined.matches);
  }
  map.check();
  out.report = report;
  return out;
}

}  // namespace reftrack
