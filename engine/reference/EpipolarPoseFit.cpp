#include "engine/reference/EpipolarPoseFit.hpp"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "engine/geometry/FundamentalMatrix.hpp"

namespace reftrack {

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

// Distance (pixels) of p2 to the epipolar line of p1 under R = exp(w) R0 and the unit
// translation direction u: F = K^-T [u]x R K^-1 (the matcher's gate measures the same).
struct EpipolarLineDistance {
  Eigen::Matrix3d Kinv;
  Eigen::Matrix3d R0;
  Eigen::Vector2d p1, p2;
  template <typename T>
  bool operator()(const T* const w, const T* const u, T* residual) const {
    // Normalised rays of both pixels.
    const Eigen::Matrix<T, 3, 1> x1 = (Kinv * p1.homogeneous()).template cast<T>();
    // R x1 = exp(w) (R0 x1).
    const Eigen::Matrix<T, 3, 1> r0x1 = R0.template cast<T>() * x1;
    Eigen::Matrix<T, 3, 1> rx1;
    ceres::AngleAxisRotatePoint(w, r0x1.data(), rx1.data());
    const Eigen::Matrix<T, 3, 1> t(u[0], u[1], u[2]);
    // The epipolar line in normalised coordinates of view 2, then in pixels: l_pix = K^-T l.
    const Eigen::Matrix<T, 3, 1> l = t.cross(rx1);
    const Eigen::Matrix<T, 3, 1> lp = Kinv.transpose().template cast<T>() * l;
    const Eigen::Matrix<T, 3, 1> q2(T(p2.x()), T(p2.y()), T(1.0));
    using std::sqrt;
    residual[0] = lp.dot(q2) / sqrt(lp[0] * lp[0] + lp[1] * lp[1] + T(1e-30));
    return true;
  }
};

double distance(const Eigen::Matrix3d& F, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector3d line = F * a.homogeneous();
  const double n = line.head<2>().norm();
  return n > 0.0 ? std::abs(line.dot(b.homogeneous())) / n
                 : std::numeric_limits<double>::infinity();
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const std::size_t k =
      std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

EpipolarPoseFit fitEpipolarPose(const Eigen::Matrix3d& K, const RigidPose& given,
                                const std::vector<Eigen::Vector2d>& p1,
                                const std::vector<Eigen::Vector2d>& p2, double inlierPx) {
  EpipolarPoseFit out;
  out.fitted = given;
  out.correspondences = static_cast<int>(std::min(p1.size(), p2.size()));
  const double baseline = given.translation().norm();
  if (out.correspondences < 6 || !(baseline > 0.0) || !given.allFinite()) return out;

  const Eigen::Matrix3d Kinv = K.inverse();
  double w[3] = {0.0, 0.0, 0.0};
  const Eigen::Vector3d u0 = given.translation() / baseline;
  double u[3] = {u0.x(), u0.y(), u0.z()};
  ceres::Problem problem;
  for (int i = 0; i < out.correspondences; ++i)
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<EpipolarLineDistance, 1, 3, 3>(
            new EpipolarLineDistance{Kinv, given.rotation(), p1[static_cast<std::size_t>(i)],
                                     p2[static_cast<std::size_t>(i)]}),
        new ceres::CauchyLoss(1.0), w, u);
  problem.SetManifold(u, new ceres::SphereManifold<3>());
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 50;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  const Eigen::Vector3d wv(w[0], w[1], w[2]), uv = Eigen::Vector3d(u[0], u[1], u[2]).normalized();
  if (summary.IsSolutionUsable() && wv.allFinite() && uv.allFinite()) {
    const Eigen::Matrix3d dR = wv.norm() > 0.0
                                   ? Eigen::AngleAxisd(wv.norm(), wv / wv.norm()).toRotationMatrix()
                                   : Eigen::Matrix3d::Identity();
    out.fitted = RigidPose(dR * given.rotation(), baseline * uv);
    out.rotationChangeDeg = wv.norm() * kDeg;
    out.translationDirectionChangeDeg = std::acos(std::clamp(uv.dot(u0), -1.0, 1.0)) * kDeg;
  }

  const Eigen::Matrix3d Fg = fundamentalMatrix(K, given), Ff = fundamentalMatrix(K, out.fitted);
  std::vector<double> dg, df;
  for (int i = 0; i < out.correspondences; ++i) {
    const Eigen::Vector2d &a = p1[static_cast<std::size_t>(i)],
                          &b = p2[static_cast<std::size_t>(i)];
    const double f = distance(Ff, a, b);
    if (!(f <= inlierPx)) continue;
    df.push_back(f);
    dg.push_back(distance(Fg, a, b));
  }
  out.inliers = static_cast<int>(df.size());
  out.givenMedianPx = quantile(dg, 0.5);
  out.givenP90Px = quantile(dg, 0.9);
  out.fittedMedianPx = quantile(df, 0.5);
  out.fittedP90Px = quantile(df, 0.9);
  return out;
}

}  // namespace reftrack
