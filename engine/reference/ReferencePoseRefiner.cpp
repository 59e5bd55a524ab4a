#include "engine/reference/ReferencePoseRefiner.hpp"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <cmath>
#include <numbers>

#include "engine/config/ConfigValue.hpp"
#include "engine/reference/MapPointReprojectionCost.hpp"

namespace reftrack {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Prior on one reference pose x = (t, r) (world -> camera) in the terms a fiducial at the world
// origin fixes well — where the origin projects (pixels) and how far the camera is from it — and
// its orientation, which a fiducial fixes far less well (the relative rotation comes from the
// matches), each in units of its SD. A camera that does not see the origin in front of it gets a
// prior on its centre instead.
struct PosePriorCost {
  PosePriorCost(const Eigen::Matrix3d& K, const Vector6d& given,
                const ReferencePoseRefinerParams& params)
      : K(K), givenR(given.tail<3>()), params(params) {
    const RigidPose T = RigidPose::fromVector6(given);
    givenC = T.cameraCentre();
    const Eigen::Vector3d origin = T.translation();  // the world origin in the camera frame
    seesOrigin = origin.z() > 1e-3;
    givenOriginPixel = seesOrigin ? Eigen::Vector2d((K * origin).hnormalized()) : Eigen::Vector2d();
    givenDistance = givenC.norm();
  }
  template <typename T>
  bool operator()(const T* const x, T* residual) const {
    // C = -R^T t: rotate -t by the inverse rotation (-r).
    const T minusR[3] = {-x[3], -x[4], -x[5]};
    const T minusT[3] = {-x[0], -x[1], -x[2]};
    T C[3];
    ceres::AngleAxisRotatePoint(minusR, minusT, C);
    const double rotationSd = params.rotationSdDeg * kDeg;
    for (int i = 0; i < 3; ++i) residual[3 + i] = (x[3 + i] - givenR[i]) / rotationSd;
    if (!seesOrigin) {
      for (int i = 0; i < 3; ++i) residual[i] = (C[i] - givenC[i]) / params.translationSdMetres;
      return true;
    }
    // The origin in the camera frame is t itself.
    const T u = (K(0, 0) * x[0] + K(0, 1) * x[1]) / x[2] + K(0, 2);
    const T v = K(1, 1) * x[1] / x[2] + K(1, 2);
    residual[0] = (u - givenOriginPixel.x()) / params.originSdPx;
    residual[1] = (v - givenOriginPixel.y()) / params.originSdPx;
    residual[2] = (ceres::sqrt(C[0] * C[0] + C[1] * C[1] + C[2] * C[2]) - givenDistance) /
                  params.translationSdMetres;
    return true;
  }
  Eigen::Matrix3d K;
  Eigen::Vector3d givenR, givenC;
  Eigen::Vector2d givenOriginPixel;
  double givenDistance = 0.0;
  bool seesOrigin = false;
  ReferencePoseRefinerParams params;
};

// MapPointReprojectionCost in units of the corner SD.
struct WhitenedReprojection {
  MapPointReprojectionCost cost;
  double sd;
  template <typename T>
  bool operator()(const T* const pose, const T* const point, T* residual) const {
    cost(pose, point, residual);
    residual[0] /= sd;
    residual[1] /= sd;
    return true;
  }
};

double rmsOf(const MultiReferenceMap& map, const std::vector<std::vector<Eigen::Vector2d>>& obs) {
  double sse = 0.0;
  int n = 0;
  for (std::size_t p = 0; p < map.points.size(); ++p)
    for (std::size_t o = 0; o < map.points[p].observations.size(); ++o) {
      const RigidPose& T =
          map.views[static_cast<std::size_t>(map.points[p].observations[o].view)].T;
      const Eigen::Vector3d X = T * map.points[p].world;
      if (!(X.z() > 0.0)) continue;
      sse += (map.camera.project(X) - obs[p][o]).squaredNorm();
      ++n;
    }
  return n > 0 ? std::sqrt(sse / n) : 0.0;
}

}  // namespace

void ReferencePoseRefinerParams::check() const {
  requireFiniteInRange("preparation.pose_prior_translation_sd_m", translationSdMetres, 1e-9, 10.0);
  requireFiniteInRange("preparation.pose_prior_rotation_sd_deg", rotationSdDeg, 1e-6, 90.0);
  requireFiniteInRange("preparation.pose_prior_origin_sd_px", originSdPx, 1e-4, 100.0);
  requireFiniteInRange("preparation.pose_refinement_corner_sd_px", cornerSdPx, 1e-3, 100.0);
  requireIntInRange("preparation.pose_refinement_iterations", maxIterations, 1, 10000);
}

ReferencePoseRefinement refineReferencePoses(MultiReferenceMap& map,
                                             const ReferencePoseRefinerParams& params) {
  params.check();
  ReferencePoseRefinement out;
  out.movedMillimetres.assign(map.views.size(), 0.0);
  out.movedDeg.assign(map.views.size(), 0.0);
  if (map.views.size() < 2 || map.points.empty()) return out;

  // The undistorted measured pixel of every observation: the correlation peak the point was
  // triangulated from where the map has it, else the corner. (Fitting the corners instead, which
  // lie up to matching.max_peak_offset_px from the peaks, pulled exact poses off them: the
  // simulator's depth RMS grew 3 -> 5 mm.)
  std::vector<cv::Point2f> pixels;
  for (const MapPoint& point : map.points)
    for (const PointObservation& o : point.observations) pixels.push_back(map.measuredPixel(o));
  const std::vector<cv::Point2f> undistorted = map.camera.undistortPixels(pixels);
  std::vector<std::vector<Eigen::Vector2d>> obs(map.points.size());
  std::size_t next = 0;
  for (std::size_t p = 0; p < map.points.size(); ++p)
    for (std::size_t o = 0; o < map.points[p].observations.size(); ++o, ++next)
      obs[p].emplace_back(undistorted[next].x, undistorted[next].y);
  out.initialRmsPx = rmsOf(map, obs);

  std::vector<Vector6d> poses(map.views.size());
  for (std::size_t v = 0; v < map.views.size(); ++v) poses[v] = map.views[v].T.toVector6();
  const std::vector<Vector6d> given = poses;
  std::vector<Eigen::Vector3d> points(map.points.size());
  for (std::size_t p = 0; p < map.points.size(); ++p) points[p] = map.points[p].world;

  ceres::Problem problem;
  const Eigen::Matrix3d K = map.camera.K();
  for (std::size_t p = 0; p < map.points.size(); ++p)
    for (std::size_t o = 0; o < map.points[p].observations.size(); ++o) {
      const std::size_t v = static_cast<std::size_t>(map.points[p].observations[o].view);
      if (!((map.views[v].T * points[p]).z() > 0.0)) continue;
      // Whitened by the corner SD: the residual is in SDs, the Cauchy scale 1 SD.
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<WhitenedReprojection, 2, 6, 3>(
              new WhitenedReprojection{MapPointReprojectionCost(K, obs[p][o]), params.cornerSdPx}),
          new ceres::CauchyLoss(1.0), poses[v].data(), points[p].data());
      ++out.observations;
    }
  if (out.observations == 0) return out;
  if (problem.HasParameterBlock(poses[0].data()))
    problem.SetParameterBlockConstant(poses[0].data());
  for (std::size_t v = 1; v < map.views.size(); ++v) {
    if (!problem.HasParameterBlock(poses[v].data())) continue;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PosePriorCost, 6, 6>(
                                 new PosePriorCost(K, given[v], params)),
                             nullptr, poses[v].data());
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_SCHUR;  // few poses, many points
  options.max_num_iterations = params.maxIterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  if (!summary.IsSolutionUsable()) return out;
  for (std::size_t v = 1; v < map.views.size(); ++v) {
    if (!poses[v].allFinite()) return out;
  }
  for (std::size_t v = 1; v < map.views.size(); ++v) {
    const RigidPose before = map.views[v].T;
    map.views[v].T = RigidPose::fromVector6(poses[v]);
    out.movedMillimetres[v] =
        1000.0 * (map.views[v].T.cameraCentre() - before.cameraCentre()).norm();
    const Eigen::AngleAxisd turn(map.views[v].T.rotation() * before.rotation().transpose());
    out.movedDeg[v] = std::abs(turn.angle()) / kDeg;
  }
  for (std::size_t p = 0; p < map.points.size(); ++p)
    if (points[p].allFinite()) map.points[p].world = points[p];
  out.finalRmsPx = rmsOf(map, obs);
  return out;
}

}  // namespace reftrack
