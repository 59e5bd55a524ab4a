#include "engine/evaluation/TrajectoryEvaluator.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/config/ConfigValue.hpp"
#include "engine/core/Error.hpp"
#include "engine/evaluation/TrajectoryAssociation.hpp"

namespace reftrack {

namespace {
constexpr double kDeg = 180.0 / std::numbers::pi;
}  // namespace

std::string toString(TrajectoryAlignment alignment) {
  switch (alignment) {
    case TrajectoryAlignment::Se3:
      return "se3";
    case TrajectoryAlignment::Sim3:
      return "sim3";
    case TrajectoryAlignment::Se3Views:
      return "se3-views";
    case TrajectoryAlignment::None:
      break;
  }
  return "none";
}

TrajectoryAlignment parseTrajectoryAlignment(const std::string& text) {
  for (TrajectoryAlignment a : {TrajectoryAlignment::None, TrajectoryAlignment::Se3,
                                TrajectoryAlignment::Sim3, TrajectoryAlignment::Se3Views})
    if (text == toString(a)) return a;
  throw Error("alignment '" + text + "' is not one of none, se3, sim3, se3-views");
}

void EvaluationParams::check() const {
  requireFiniteInRange("evaluation.max_time_difference", maxTimeDifference, 0.0, 1e6);
  requireFiniteInRange("evaluation.cube_side", cubeSide, 1e-6, 1e3);
  for (int a = 0; a < 3; ++a) requireFiniteInRange("evaluation.cube_base", cubeBase[a], -1e6, 1e6);
}

ErrorStats ErrorStats::of(std::vector<double> values) {
  ErrorStats s;
  s.count = values.size();
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  double sum = 0, sumSq = 0;
  for (double v : values) sum += v, sumSq += v * v;
  const double n = static_cast<double>(values.size());
  s.mean = sum / n;
  s.rmse = std::sqrt(sumSq / n);
  s.max = values.back();
  auto quantile = [&](double q) {
    const double pos = q * (n - 1);
    const std::size_t lo = static_cast<std::size_t>(std::floor(pos));
    const std::size_t hi = std::min(lo + 1, values.size() - 1);
    return values[lo] + (pos - lo) * (values[hi] - values[lo]);
  };
  s.median = quantile(0.5);
  s.p95 = quantile(0.95);
  return s;
}

std::vector<Eigen::Vector3d> cubeVertices(double side) {
  std::vector<Eigen::Vector3d> v;
  const double h = 0.5 * side;
  for (double z : {0.0, side})
    for (double y : {-h, h})
      for (double x : {-h, h}) v.emplace_back(x, y, z);
  return v;
}

TrajectoryEvaluation evaluateTrajectory(const TumTrajectory& groundTruth,
                                        const TumTrajectory& estimate,
                                        const EvaluationParams& params,
                                        const PinholeCamera* camera) {
  params.check();
  if (groundTruth.poses.empty()) throw Error("the ground-truth trajectory holds no poses");
  if (estimate.poses.empty()) throw Error("the estimated trajectory holds no poses");
  const std::vector<AssociatedPair> pairs =
      associateByTimestamp(groundTruth, estimate, params.maxTimeDifference);
  if (pairs.empty())
    throw Error("no estimated pose lies within " + std::to_string(params.maxTimeDifference) +
                " s of a ground-truth timestamp; check the time bases or raise --max-dt");

  TrajectoryEvaluation ev;
  ev.groundTruthFrames = groundTruth.poses.size();
  ev.estimateFrames = estimate.poses.size();
  ev.associatedFrames = pairs.size();
  ev.trackedFraction = static_cast<double>(pairs.size()) / groundTruth.poses.size();

  if (params.alignment != TrajectoryAlignment::None) {
    if (pairs.size() < 3)
      throw Error(toString(params.alignment) + " alignment needs at least 3 associated poses");
    const bool views = params.alignment == TrajectoryAlignment::Se3Views;
    // Per frame: the centre, and with views three points of the view at the scene's depth.
    std::vector<Eigen::Vector3d> inCamera = {Eigen::Vector3d::Zero()};
    if (views) {
      std::vector<double> depth;
      for (const AssociatedPair& p : pairs)
        depth.push_back(groundTruth.poses[p.groundTruth].worldToCamera.cameraCentre().norm());
      std::nth_element(depth.begin(), depth.begin() + static_cast<long>(depth.size() / 2),
                       depth.end());
      const double d = std::max(1e-3, depth[depth.size() / 2]);
      inCamera = {Eigen::Vector3d(0, 0, d), Eigen::Vector3d(0.5 * d, 0, d),
                  Eigen::Vector3d(0, 0.5 * d, d), Eigen::Vector3d::Zero()};
    }
    const long n = static_cast<long>(pairs.size() * inCamera.size());
    Eigen::Matrix3Xd src(3, n), dst(3, n);
    long k = 0;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const RigidPose& e = estimate.poses[pairs[i].estimate].worldToCamera;
      const RigidPose& g = groundTruth.poses[pairs[i].groundTruth].worldToCamera;
      for (const Eigen::Vector3d& q : inCamera) {
        src.col(k) = e.rotation().transpose() * (q - e.translation());
        dst.col(k) = g.rotation().transpose() * (q - g.translation());
        ++k;
      }
    }
    const bool withScale = params.alignment == TrajectoryAlignment::Sim3;
    const Eigen::Matrix4d T = Eigen::umeyama(src, dst, withScale);
    const Eigen::Matrix3d sR = T.topLeftCorner<3, 3>();
    ev.alignmentScale = withScale ? std::cbrt(sR.determinant()) : 1.0;
    if (!(ev.alignmentScale > 0.0) || !T.allFinite())
      throw Error(toString(params.alignment) +
                  " alignment failed: the estimated camera centres are degenerate (all equal?)");
    ev.alignment = RigidPose(sR / ev.alignmentScale, T.topRightCorner<3, 1>());
    ev.aligned = true;
  }

  // Poses of the estimate in the ground-truth world: orientation R_e R_a^T, centre s R_a c_e + t_a.
  std::vector<RigidPose> est(pairs.size()), gt(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    gt[i] = groundTruth.poses[pairs[i].groundTruth].worldToCamera;
    const RigidPose& e = estimate.poses[pairs[i].estimate].worldToCamera;
    const Eigen::Matrix3d R = e.rotation() * ev.alignment.rotation().transpose();
    const Eigen::Vector3d c = ev.alignmentScale * (ev.alignment.rotation() * e.cameraCentre()) +
                              ev.alignment.translation();
    est[i] = RigidPose(R, -R * c);
  }

  std::vector<Eigen::Vector3d> cube = cubeVertices(params.cubeSide);
  for (Eigen::Vector3d& X : cube) X += params.cubeBase;
  std::vector<double> ateT, ateR, cubePx;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    FrameEvaluation f;
    f.timestamp = groundTruth.poses[pairs[i].groundTruth].timestamp;
    f.trueCentre = gt[i].cameraCentre();
    f.estimatedCentre = est[i].cameraCentre();
    f.translationErrorMm = 1000.0 * (f.trueCentre - f.estimatedCentre).norm();
    f.rotationErrorDeg = RigidPose::rotationDistance(gt[i], est[i]) * kDeg;
    ateT.push_back(f.translationErrorMm);
    ateR.push_back(f.rotationErrorDeg);
    if (camera) {
      double sum = 0;
      int n = 0;
      for (const Eigen::Vector3d& X : cube) {
        const Eigen::Vector3d a = gt[i] * X, b = est[i] * X;
        if (a.z() <= 0 || b.z() <= 0) continue;  // behind a camera: no image position
        const double e = (camera->project(a) - camera->project(b)).norm();
        cubePx.push_back(e);
        sum += e, ++n;
      }
      if (n > 0) f.cubeErrorPx = sum / n;
    }
    ev.frames.push_back(f);
  }
  ev.ateTranslationMm = ErrorStats::of(ateT);
  ev.ateRotationDeg = ErrorStats::of(ateR);
  if (camera) ev.cubeErrorPx = ErrorStats::of(cubePx);

  std::vector<double> rpeT, rpeR;
  for (std::size_t i = 1; i < pairs.size(); ++i) {
    const RigidPose dGt = gt[i] * gt[i - 1].inverse(), dEst = est[i] * est[i - 1].inverse();
    const RigidPose e = dGt.inverse() * dEst;
    rpeT.push_back(1000.0 * e.translation().norm());
    rpeR.push_back(RigidPose::rotationDistance(e, RigidPose::identity()) * kDeg);
    ev.rpeTimestamps.push_back(ev.frames[i].timestamp);
  }
  ev.rpeTranslationMm = ErrorStats::of(rpeT);
  ev.rpeRotationDeg = ErrorStats::of(rpeR);
  ev.rpeTranslationMmPerPair = rpeT;
  ev.rpeRotationDegPerPair = rpeR;

  // Jitter over runs of three consecutive ground-truth frames (see the header).
  double sumSqMm = 0, sumSqPx = 0;
  std::size_t nMm = 0, nPx = 0;
  for (std::size_t i = 1; i + 1 < pairs.size(); ++i) {
    if (pairs[i].groundTruth != pairs[i - 1].groundTruth + 1 ||
        pairs[i + 1].groundTruth != pairs[i].groundTruth + 1)
      continue;
    for (const Eigen::Vector3d& X : cube) {
      Eigen::Vector3d e[3];
      Eigen::Vector2d p[3];
      bool visible = true;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d a = gt[i - 1 + k] * X, b = est[i - 1 + k] * X;
        e[k] = b - a;
        visible = visible && a.z() > 0 && b.z() > 0;
        if (camera && visible) p[k] = camera->project(b) - camera->project(a);
      }
      const Eigen::Vector3d a3 = e[2] - 2 * e[1] + e[0];
      sumSqMm += 1e6 * a3.squaredNorm(), nMm += 3;
      if (camera && visible) {
        const Eigen::Vector2d a2 = p[2] - 2 * p[1] + p[0];
        sumSqPx += a2.squaredNorm(), nPx += 2;
      }
    }
  }
  if (nMm > 0) ev.jitterMm = std::sqrt(sumSqMm / nMm / 6.0);
  if (nPx > 0) ev.jitterPx = std::sqrt(sumSqPx / nPx / 6.0);
  return ev;
}

}  // namespace reftrack
