#include "engine/mapping/UnpreparedInitializer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "engine/core/Error.hpp"
#include "engine/reference/ReferencePoseRefiner.hpp"
#include "engine/relocalisation/Relocaliser.hpp"

namespace reftrack {

namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
// A marked point's ray must meet the plane at least this steeply (degrees): at a grazing angle
// a pixel's error moves the point along the plane without bound.
constexpr double kMinRayPlaneAngleDeg = 5.0;

std::string fixed(double v, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// The median depth (first camera's z) of the motion's inliers triangulated with |t| = 1: along
// the first ray, the depth that puts the point on the second ray (least squares).
double medianDepthAtUnitBaseline(const PinholeCamera& camera, const TwoViewMotion& m) {
  const Eigen::Matrix3d Kinv = camera.K().inverse();
  const Eigen::Matrix3d& R = m.firstToSecond.rotation();
  const Eigen::Vector3d& t = m.firstToSecond.translation();
  std::vector<double> depths;
  for (std::size_t i = 0; i < m.inlierFirst.size(); ++i) {
    const Eigen::Vector3d r0 = Kinv * Eigen::Vector3d(m.inlierFirst[i].x, m.inlierFirst[i].y, 1);
    const Eigen::Vector3d r1 = Kinv * Eigen::Vector3d(m.inlierSecond[i].x, m.inlierSecond[i].y, 1);
    const Eigen::Vector3d a = r1.cross(R * r0), b = r1.cross(t);
    if (!(a.squaredNorm() > 1e-18)) continue;
    const double lambda = -b.dot(a) / a.squaredNorm();
    if (lambda > 0 && std::isfinite(lambda)) depths.push_back(lambda);  // r0.z() == 1
  }
  return median(depths);
}

// Direction of reference 1's translation seen from reference 0 (its centre in 0's frame).
double angleBetweenDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double c = a.normalized().dot(b.normalized());
  return std::acos(std::clamp(c, -1.0, 1.0)) * kRadToDeg;
}

// Where the first camera's ray through `pixel` (as recorded) meets the plane (camera frame).
Eigen::Vector3d onPlane(const PinholeCamera& camera, const cv::Point2d& pixel,
                        const Eigen::Vector3d& normal, const Eigen::Vector3d& pointOnPlane) {
  const std::vector<cv::Point2f> u = camera.undistortPixels(
      {cv::Point2f(static_cast<float>(pixel.x), static_cast<float>(pixel.y))});
  const Eigen::Vector3d ray =
      (camera.K().inverse() * Eigen::Vector3d(u[0].x, u[0].y, 1.0)).normalized();
  const double along = normal.dot(ray);
  const double angle = std::asin(std::min(1.0, std::abs(along))) * kRadToDeg;
  const double lambda = normal.dot(pointOnPlane) / along;
  // Appended piece by piece: GCC 12's -Wrestrict misfires on "(" + std::string.
  std::string where = "(";
  where.append(fixed(pixel.x, 1)).append(", ").append(fixed(pixel.y, 1)).append(")");
  if (!std::isfinite(lambda) || !(lambda > 0.0))
    throw Error("the distance's point " + where +
                " does not lie on the scene's dominant plane in front of the first camera: mark "
                "two points on the plane (the desk, the wall), or give --baseline");
  if (angle < kMinRayPlaneAngleDeg)
    throw Error("the distance's point " + where + " is seen at " + fixed(angle, 1) +
                " deg to the scene's plane (at least " + fixed(kMinRayPlaneAngleDeg, 0) +
                " needed): mark points nearer the image's middle, or give --baseline");
  return lambda * ray;
}

// The motions a plane's homography of the map's two-view matches allows (its corner and the
// peak it was triangulated from; cv::decomposeHomographyMat, the decompositions that keep the
// plane's inliers in front of both cameras; |t| = 1).
std::vector<RigidPose> planeMotionsOf(const MultiReferenceMap& map, const PinholeCamera& camera,
                                      double thresholdPx) {
  std::vector<cv::Point2f> a, b;
  for (const MapPoint& point : map.points) {
    if (point.observations.size() != 2) continue;
    a.push_back(map.measuredPixel(point.observations[0]));
    b.push_back(map.measuredPixel(point.observations[1]));
  }
  if (a.size() < 8) return {};
  a = camera.undistortPixels(a);
  b = camera.undistortPixels(b);
  cv::Mat mask;
  const cv::Mat H = cv::findHomography(a, b, cv::RANSAC, thresholdPx, mask);
  if (H.empty()) return {};
  cv::Mat K;
  cv::eigen2cv(camera.K(), K);
  std::vector<cv::Mat> rotations, translations, normals;
  cv::decomposeHomographyMat(H, K, rotations, translations, normals);
  const Eigen::Matrix3d Kinv = camera.K().inverse();
  std::vector<cv::Point2f> na, nb;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!mask.at<unsigned char>(static_cast<int>(i))) continue;
    for (auto [from, to] : {std::pair{&a[i], &na}, std::pair{&b[i], &nb}}) {
      const Eigen::Vector3d r = Kinv * Eigen::Vector3d(from->x, from->y, 1.0);
      to->emplace_back(static_cast<float>(r.x()), static_cast<float>(r.y()));
    }
  }
  std::vector<int> visible;
  cv::filterHomographyDecompByVisibleRefpoints(rotations, normals, na, nb, visible);
  std::vector<RigidPose> out;
  for (int i : visible) {
    Eigen::Matrix3d R;
    Eigen::Vector3d t;
    cv::cv2eigen(rotations[static_cast<std::size_t>(i)], R);
    cv::cv2eigen(translations[static_cast<std::size_t>(i)], t);
    if (R.allFinite() && t.allFinite() && t.norm() > 1e-9) out.emplace_back(R, t.normalized());
  }
  return out;
}

}  // namespace

UnpreparedInitializer::UnpreparedInitializer(PinholeCamera camera, MapExtenderParams params,
                                             UnpreparedMapParams unprepared)
    : camera_(std::move(camera)), params_(std::move(params)), unprepared_(std::move(unprepared)) {
  camera_.check();
  params_.check();
  unprepared_.check();
}

int UnpreparedInitializer::steps(int references) const {
  // The keypoints, each round of each start (the essential matrix's and at most four of planes'),
  // the plane and scale, the final preparation, then one step per added reference and the
  // closing adjustment.
  return 1 + 5 * unprepared_.refinementRounds + 2 + (references > 2 ? references - 2 + 1 : 0);
}

// Rounds of corner matching on a start pose and refinement from those matches; after each, the
// world is put on the dominant plane of the points, so the next round's matching warps its
// windows by that plane (the matcher's world z = 0 hypothesis, a marker's plane in a prepared
// scene). The cost scores the result against other starts: per corner of reference 0, its
// point's squared reprojection error in SDs (the mean of its two observations) capped at
// kUnmatchedCost, and the cap for a corner without a point (MSAC): a pose that matches fewer
// corners, or fits them worse, costs more.
UnpreparedInitializer::Refined UnpreparedInitializer::refine(
    const std::vector<ReferenceImage>& pair, const RigidPose& start, double length,
    const StepProgress& step) const {
  constexpr double kUnmatchedCost = 9.0;  // a point 3 SDs off costs as much as no point
  ReferencePreparerParams roundParams = params_.preparation;
  roundParams.relocalisation.enabled = false;
  roundParams.refinePoses = roundParams.refineGivenPoses = false;
  ReferencePoseRefinerParams refiner = params_.preparation.poseRefinement;
  refiner.originSdPx = 100.0;    // no fiducial at the world origin
  refiner.rotationSdDeg = 10.0;  // the start's rotation is good to a fraction of this
  refiner.translationSdMetres = 0.05 * length;  // the length is kept exactly below
  refiner.maxIterations = std::max(refiner.maxIterations, 100);
  Refined out;
  out.second = start;
  for (int round = 0; round < unprepared_.refinementRounds; ++round) {
    if (step) step("matching round " + std::to_string(round + 1));
    ReferencePreparerParams p = roundParams;
    if (round == 0) {
      p.matching.maxEpipolarDistancePx =
          std::max(p.matching.maxEpipolarDistancePx, unprepared_.bootstrapEpipolarDistancePx);
      p.matching.maxReprojectionErrorPx =
          std::max(p.matching.maxReprojectionErrorPx, unprepared_.bootstrapReprojectionErrorPx);
    }
    MultiReferenceMap map =
        MultiReferencePreparer(camera_, p)
            .prepare(pair, std::vector<RigidPose>{out.worldToFirst, out.second * out.worldToFirst},
                     "unprepared")
            .map;
    UnpreparedRound r;
    r.points = static_cast<int>(map.points.size());
    const ReferencePoseRefinement refined = refineReferencePoses(map, refiner);
    r.rmsBeforePx = refined.initialRmsPx;
    r.rmsAfterPx = refined.finalRmsPx;
    const RigidPose after = map.views[1].T * out.worldToFirst.inverse();
    if (!after.allFinite() || !(after.translation().norm() > 0.0))
      throw Error("the pose refinement failed");
    r.turnedDeg = RigidPose::rotationDistance(out.second, after) * kRadToDeg;
    r.directionDeg = angleBetweenDeg(out.second.cameraCentre(), after.cameraCentre());
    // The length stays the chosen one: the refinement's prior only held it loosely. Scaling the
    // points about the first camera is the same gauge change.
    const double toLength = length / after.translation().norm();
    out.second = RigidPose(after.rotation(), after.translation() * toLength);
    out.points.clear();
    for (const MapPoint& point : map.points)
      out.points.push_back(toLength * (out.worldToFirst * point.world));
    out.rounds.push_back(r);
    if (round + 1 == unprepared_.refinementRounds) {
      // The cost, at the refined pose and points.
      std::vector<cv::Point2f> pixels;
      for (const MapPoint& point : map.points)
        for (const PointObservation& o : point.observations) pixels.push_back(map.measuredPixel(o));
      const std::vector<cv::Point2f> undistorted = camera_.undistortPixels(pixels);
      const double sd = params_.preparation.poseRefinement.cornerSdPx;
      std::size_t next = 0;
      out.cost =
          kUnmatchedCost * static_cast<double>(map.views[0].corners.size() - map.points.size());
      for (const MapPoint& point : map.points) {
        double squares = 0.0;
        for (const PointObservation& o : point.observations) {
          const Eigen::Vector3d X = map.views[static_cast<std::size_t>(o.view)].T * point.world;
          const cv::Point2f& q = undistorted[next++];
          squares +=
              X.z() > 0.0 ? (map.camera.project(X) - Eigen::Vector2d(q.x, q.y)).squaredNorm() : 1e6;
        }
        out.cost += std::min(kUnmatchedCost,
                             squares / static_cast<double>(point.observations.size()) / (sd * sd));
      }
    }
    if (round + 1 == unprepared_.refinementRounds)
      out.cornerPlaneMotions = planeMotionsOf(map, camera_, unprepared_.ransacThresholdPx);
    try {
      out.plane =
          placeOnDominantPlane(out.points, {Eigen::Vector3d::Zero(), out.second.cameraCentre()});
      // The placement's frame (x along camera 0's x on the plane, z its normal toward the
      // cameras) in camera 0's coordinates: X_camera0 = R X_world + base.
      out.worldToFirst = RigidPose(out.plane->rotation, out.plane->base);
      out.noPlane.clear();
    } catch (const Error& e) {
      out.plane.reset();
      out.noPlane = e.what();
      out.worldToFirst = RigidPose{};
    }
  }
  return out;
}

UnpreparedMap UnpreparedInitializer::build(
    const std::vector<ReferenceImage>& images, const MetricScale& scale,
    const StepProgress& progress, const MultiReferencePreparer::PairProgress& pairs) const {
  const auto step = [&](const std::string& what) {
    if (progress) progress(what);
  };
  if (images.size() < 2)
    throw Error("an unprepared map needs at least 2 reference images, got " +
                std::to_string(images.size()));
  for (const ReferenceImage& r : images) checkReferenceImage(r, camera_);
  for (std::size_t a = 0; a < images.size(); ++a)
    for (std::size_t b = a + 1; b < images.size(); ++b)
      checkDistinctReferenceImages(images[a], images[b]);
  scale.check(camera_.imageSize());

  UnpreparedMap out;
  UnpreparedMapReport& report = out.report;
  report.scale = scale;
  const std::string pairName = "'" + images[0].name + "' and '" + images[1].name + "'";

  // 1. The motion from the keypoints.
  step("keypoints, essential matrix and homography");
  const TwoViewMotionEstimator estimator(camera_, unprepared_);
  report.motion = estimator.estimate(images[0].image, images[1].image);
  if (!report.motion.usable())
    throw Error("references " + pairName + " cannot start a map: " + report.motion.refusal);
  report.essentialPose = report.motion.firstToSecond;

  // The baseline's length while the rounds run: the user's, or (a distance on the plane, known
  // only once the plane is) the one that puts the scene's median depth at 1 m, so the
  // preparation's metric gates (depth range, minimum baseline) see a plausible scene.
  double length = scale.metres;
  if (scale.kind == MetricScale::Kind::Distance) {
    const double depth = medianDepthAtUnitBaseline(camera_, report.motion);
    if (!std::isfinite(depth) || !(depth > 0.0))
      throw Error("references " + pairName +
                  " cannot start a map: their matches triangulate "
                  "behind the cameras; move the camera sideways and try again");
    length = 1.0 / depth;
  }

  // 2. Refined from each start: the essential matrix's motion and the plane homography's; the
  // start whose refinement fits the corners best wins. (Real desk clip, references 200 and 240:
  // the essential matrix of 51 keypoint inliers started 2.0 deg off the true rotation and its
  // refinement stayed 1.8 deg off, at a worse fit than the plane's start, 0.15 deg off.)
  std::vector<std::pair<std::string, RigidPose>> starts = {
      {"essential matrix", report.motion.firstToSecond}};
  for (const RigidPose& m : report.motion.planeMotions)
    if (starts.size() < 3) starts.emplace_back("plane homography of the keypoints", m);
  const std::vector<ReferenceImage> pair = {images[0], images[1]};
  std::optional<Refined> best;
  std::string failures;
  const auto refineFrom = [&](const std::string& name, const RigidPose& motion) {
    try {
      Refined r =
          refine(pair, RigidPose(motion.rotation(), motion.translation() * length), length, step);
      r.start = name;
      if (!best || r.cost < best->cost) best = std::move(r);
    } catch (const Error& e) {
      failures += (failures.empty() ? "" : "; ") + name + ": " + e.what();
    }
  };
  for (const auto& [name, motion] : starts) refineFrom(name, motion);
  // Then the best one's corner matches, sub-pixel and on a plane many more than the keypoints,
  // give a plane homography whose motions start again.
  if (best) {
    const std::vector<RigidPose> again = best->cornerPlaneMotions;
    for (const RigidPose& m : again) {
      bool known = false;
      for (const auto& [name, motion] : starts)
        known = known || (RigidPose::rotationDistance(motion, m) * kRadToDeg < 0.02 &&
                          angleBetweenDeg(motion.cameraCentre(), m.cameraCentre()) < 0.2);
      if (known || starts.size() >= 5) continue;
      starts.emplace_back("plane homography of the corners", m);
      refineFrom(starts.back().first, m);
    }
  }
  if (!best)
    throw Error("references " + pairName +
                " cannot start a map: their corners do not match on "
                "the motion their keypoints give (" +
                failures + "); move the camera sideways over a textured scene and try again");
  report.start = best->start;
  report.starts = static_cast<int>(starts.size());
  report.rounds = best->rounds;
  RigidPose second = best->second;
  RigidPose worldToFirst = best->worldToFirst;
  const std::optional<ScenePlacement>& plane = best->plane;

  // 3. The scale.
  step("plane and scale");
  if (plane) {
    report.onPlane = true;
    report.planePoints = plane->planePoints;
    report.planeConsideredPoints = plane->consideredPoints;
    report.planeRmsMetres = plane->planeRmsMetres;
  } else {
    report.planeNote = best->noPlane;
  }
  if (scale.kind == MetricScale::Kind::Distance) {
    if (!plane)
      throw Error(
          "a distance between two marked points needs the scene's dominant plane, and "
          "none was found (" +
          best->noPlane + "); give --baseline instead");
    const Eigen::Vector3d n = plane->rotation.col(2);
    const Eigen::Vector3d a = onPlane(camera_, scale.first, n, plane->base);
    const Eigen::Vector3d b = onPlane(camera_, scale.second, n, plane->base);
    const double k = scale.metres / (a - b).norm();
    if (!std::isfinite(k) || !(k > 0.0))
      throw Error(
          "the distance's two points meet the plane at one place: mark two points far "
          "apart on the plane, or give --baseline");
    length *= k;
    report.planeRmsMetres *= k;
    second = RigidPose(second.rotation(), second.translation() * k);
    worldToFirst = RigidPose(plane->rotation, plane->base * k);
    report.distanceFirst = worldToFirst.inverse() * (a * k);
    report.distanceSecond = worldToFirst.inverse() * (b * k);
  }
  report.baselineMetres = length;
  report.refinedPose = second;

  // 4. The map, prepared as `prepare --poses` prepares one.
  step("preparing the map");
  const std::vector<RigidPose> poses = {worldToFirst, second * worldToFirst};
  const std::string source =
      "unprepared (essential matrix of the keypoints, refined from the corner matches; " +
      std::string(report.onPlane ? "world on the dominant plane" : "world = reference 0's camera") +
      "; " + scale.toString() + ")";
  const MultiReferencePreparer preparer(camera_, params_.preparation);
  out.prepared = preparer.prepare(pair, poses, source, pairs);

  // 5. References 2..: located in the map, added as `extend` adds them.
  if (images.size() > 2) {
    const Relocaliser locator(out.prepared.map, params_.tracker.relocalisation);
    MapExtender extender(out.prepared.map, params_);
    for (std::size_t i = 2; i < images.size(); ++i) {
      step("adding reference " + std::to_string(i) + " (" + images[i].name + ")");
      const RelocalisationAttempt found = locator.locate(images[i].image, true);
      if (!found.candidate)
        throw Error("reference '" + images[i].name + "' cannot be located in the map of " +
                    pairName + " (" + found.message +
                    "): take it where it sees much of what the first two see");
      const std::string why =
          extender.add(images[i].image, static_cast<int>(i), found.candidate->worldToCamera);
      if (!why.empty())
        throw Error("reference '" + images[i].name + "' cannot be added to the map: " + why);
    }
    step("closing bundle adjustment");
    report.closingAdjustment = extender.finish();
    report.added = extender.added();
    MultiReferenceMap map = extender.map();
    if (params_.preparation.relocalisation.enabled)
      buildReferenceKeypoints(map, params_.preparation.relocalisation);
    map.check();
    out.prepared.map = std::move(map);
  }
  return out;
}

}  // namespace reftrack
