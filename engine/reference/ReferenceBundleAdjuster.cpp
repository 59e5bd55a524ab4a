#include "engine/reference/ReferenceBundleAdjuster.hpp"

#include <ceres/ceres.h>

#include <cmath>
#include <memory>
#include <string>

#include "engine/core/Error.hpp"
#include "engine/reference/MapPointReprojectionCost.hpp"

namespace reftrack {

namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

std::unique_ptr<ceres::LossFunction> makeLoss(const BundleAdjustmentParams& p) {
  if (p.loss == "huber") return std::make_unique<ceres::HuberLoss>(p.lossScalePx);
  if (p.loss == "cauchy") return std::make_unique<ceres::CauchyLoss>(p.lossScalePx);
  return nullptr;  // "none": plain least squares
}

// Undistorted measured pixel of every observation, per point in observation order: its
// correlation peak (PointObservation::peak, the pixel the point was triangulated from), or its
// corner where the map has none (MultiReferenceMap::measuredPixel; the pixels are stored as
// detected, with lens distortion).
std::vector<std::vector<Eigen::Vector2d>> undistortedMeasurements(const MultiReferenceMap& map) {
  std::vector<cv::Point2f> pixels;
  for (const MapPoint& p : map.points)
    for (const PointObservation& o : p.observations) pixels.push_back(map.measuredPixel(o));
  const std::vector<cv::Point2f> undistorted = map.camera.undistortPixels(pixels);
  std::vector<std::vector<Eigen::Vector2d>> out(map.points.size());
  std::size_t next = 0;
  for (std::size_t i = 0; i < map.points.size(); ++i)
    for (std::size_t k = 0; k < map.points[i].observations.size(); ++k, ++next)
      out[i].emplace_back(undistorted[next].x, undistorted[next].y);
  return out;
}

void checkObservations(const MultiReferenceMap& map) {
  for (std::size_t i = 0; i < map.points.size(); ++i)
    for (const PointObservation& o : map.points[i].observations) {
      if (o.view < 0 || o.view >= map.size())
        throw Error("bundle adjustment: point " + std::to_string(i) + " names reference " +
                    std::to_string(o.view) + " of " + std::to_string(map.size()));
      const auto corners = map.views[static_cast<std::size_t>(o.view)].corners.size();
      if (o.corner < 0 || static_cast<std::size_t>(o.corner) >= corners)
        throw Error("bundle adjustment: point " + std::to_string(i) + " names corner " +
                    std::to_string(o.corner) + " of reference " + std::to_string(o.view) +
                    ", which has " + std::to_string(corners));
    }
}

// The gauge rule (header): anchored views are determined; a non-anchored view becomes determined
// when it sees at least minPoints points that two determined views see; repeated to closure.
std::vector<bool> determinedViews(const MultiReferenceMap& map, int minPoints) {
  std::vector<bool> determined(map.views.size());
  for (std::size_t v = 0; v < map.views.size(); ++v) determined[v] = map.views[v].anchored;
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<int> support(map.views.size(), 0);
    for (const MapPoint& p : map.points) {
      int determinedObservers = 0;
      for (const PointObservation& o : p.observations)
        if (determined[static_cast<std::size_t>(o.view)]) ++determinedObservers;
      if (determinedObservers < 2) continue;
      for (const PointObservation& o : p.observations) ++support[static_cast<std::size_t>(o.view)];
    }
    for (std::size_t v = 0; v < map.views.size(); ++v)
      if (!determined[v] && support[v] >= minPoints) determined[v] = changed = true;
  }
  return determined;
}

double reprojectionError(const Eigen::Matrix3d& K, const RigidPose& T, const Eigen::Vector3d& X,
                         const Eigen::Vector2d& observed) {
  const Eigen::Vector3d q = K * (T * X);
  return (q.head<2>() / q.z() - observed).norm();
}

struct Observation {
  int point = -1, view = -1;
  Eigen::Vector2d pixel;
  double initialError = 0.0;
};

}  // namespace

ReferenceBundleAdjuster::ReferenceBundleAdjuster(BundleAdjustmentParams params)
    : params_(std::move(params)) {
  params_.check();
}

BundleAdjustmentReport ReferenceBundleAdjuster::adjust(MultiReferenceMap& map) const {
  const std::size_t nViews = map.views.size();
  const Eigen::Matrix3d& K = map.camera.K();
  checkObservations(map);
  const auto measured = undistortedMeasurements(map);
  const std::vector<bool> determined = determinedViews(map, params_.minDeterminedPoints);

  BundleAdjustmentReport report;
  report.views.resize(nViews);
  for (std::size_t v = 0; v < nViews; ++v) {
    report.views[v].anchored = map.views[v].anchored;
    report.views[v].refined = determined[v] && !map.views[v].anchored;
    if (report.views[v].refined) ++report.viewsRefined;
    if (!determined[v]) ++report.viewsHeld;
  }

  // Parameter blocks: pose 6-vectors of every view, point copies.
  std::vector<Vector6d> poses(nViews);
  for (std::size_t v = 0; v < nViews; ++v) poses[v] = map.views[v].T.toVector6();
  std::vector<Eigen::Vector3d> points(map.points.size());
  for (std::size_t i = 0; i < map.points.size(); ++i) points[i] = map.points[i].world;

  // Observations of the problem: determined views only (a held view's pose is not trusted to
  // place points), in front of the camera, of points with at least two such observations.
  std::vector<Observation> observations;
  for (std::size_t i = 0; i < map.points.size(); ++i) {
    std::vector<Observation> ofPoint;
    for (std::size_t k = 0; k < map.points[i].observations.size(); ++k) {
      const PointObservation& o = map.points[i].observations[k];
      const auto v = static_cast<std::size_t>(o.view);
      if (!determined[v]) continue;
      if (!((map.views[v].T * points[i]).z() > 0.0)) {
        ++report.skippedBehindCamera;
        continue;
      }
      const Eigen::Vector2d& pixel = measured[i][k];
      ofPoint.push_back({static_cast<int>(i), o.view, pixel,
                         reprojectionError(K, map.views[v].T, points[i], pixel)});
    }
    if (ofPoint.size() < 2) continue;
    ++report.pointsRefined;
    observations.insert(observations.end(), ofPoint.begin(), ofPoint.end());
  }
  report.observations = static_cast<int>(observations.size());

  const std::unique_ptr<ceres::LossFunction> loss = makeLoss(params_);
  ceres::Problem::Options problemOptions;
  problemOptions.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problemOptions);
  std::vector<bool> viewInProblem(nViews, false);
  for (const Observation& o : observations) {
    const auto v = static_cast<std::size_t>(o.view);
    problem.AddResidualBlock(MapPointReprojectionCost::create(K, o.pixel), loss.get(),
                             poses[v].data(), points[static_cast<std::size_t>(o.point)].data());
    viewInProblem[v] = true;
  }
  for (std::size_t v = 0; v < nViews; ++v)
    if (viewInProblem[v] && !report.views[v].refined)
      problem.SetParameterBlockConstant(poses[v].data());

  if (observations.empty()) {
    report.converged = true;
    report.solverMessage = "no observations to adjust";
    return report;
  }

  ceres::Solver::Options options;
  // Few references and many points: the Schur complement on the poses is small and dense.
  options.linear_solver_type = ceres::DENSE_SCHUR;
  options.max_num_iterations = params_.maxIterations;
  // Tight tolerances: the poses must settle to well under a millimetre (the test's 1 mm).
  options.function_tolerance = 1e-12;
  options.gradient_tolerance = 1e-12;
  options.parameter_tolerance = 1e-12;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  report.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  report.converged = summary.termination_type == ceres::CONVERGENCE;
  report.solverMessage = summary.message;

  // Write back: refined poses and every point in the problem (others were not touched).
  for (std::size_t v = 0; v < nViews; ++v) {
    if (!report.views[v].refined) continue;
    const RigidPose before = map.views[v].T;
    map.views[v].T = RigidPose::fromVector6(poses[v]);
    report.views[v].movedMetres = (map.views[v].T.cameraCentre() - before.cameraCentre()).norm();
    report.views[v].movedDeg = RigidPose::rotationDistance(map.views[v].T, before) * kRadToDeg;
  }
  for (std::size_t i = 0; i < map.points.size(); ++i) map.points[i].world = points[i];

  // Report: inliers by their final error; RMS before and after over the same inliers.
  double sumInitial = 0.0, sumFinal = 0.0;
  int inliers = 0;
  std::vector<double> viewInitial(nViews, 0.0), viewFinal(nViews, 0.0);
  std::vector<int> viewInliers(nViews, 0);
  for (const Observation& o : observations) {
    const auto v = static_cast<std::size_t>(o.view);
    ViewAdjustment& va = report.views[v];
    ++va.observations;
    const double e =
        reprojectionError(K, map.views[v].T, points[static_cast<std::size_t>(o.point)], o.pixel);
    if (e > params_.outlierThresholdPx) {
      ++va.outliers;
      ++report.outliers;
      continue;
    }
    sumInitial += o.initialError * o.initialError;
    sumFinal += e * e;
    ++inliers;
    viewInitial[v] += o.initialError * o.initialError;
    viewFinal[v] += e * e;
    ++viewInliers[v];
  }
  if (inliers > 0) {
    report.initialRmsPx = std::sqrt(sumInitial / inliers);
    report.finalRmsPx = std::sqrt(sumFinal / inliers);
  }
  for (std::size_t v = 0; v < nViews; ++v)
    if (viewInliers[v] > 0) {
      report.views[v].initialRmsPx = std::sqrt(viewInitial[v] / viewInliers[v]);
      report.views[v].finalRmsPx = std::sqrt(viewFinal[v] / viewInliers[v]);
    }
  return report;
}

}  // namespace reftrack
