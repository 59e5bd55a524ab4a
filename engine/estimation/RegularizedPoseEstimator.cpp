#include "engine/estimation/RegularizedPoseEstimator.hpp"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <opencv2/calib3d.hpp>

#include "engine/estimation/EpipolarDistanceCost.hpp"
#include "engine/estimation/ThreeViewReprojectionCost.hpp"

namespace reftrack {

namespace {

// alpha ||x - x_pred||^2_{Omega^-1} as 6 whitened residuals sqrt(alpha) L^T (x - x_pred),
// with Omega^-1 = L L^T.
struct MotionPriorCost {
  MotionPriorCost(const Matrix6d& sqrtInformation, const Vector6d& mean)
      : S(sqrtInformation), mean(mean) {}
  template <typename T>
  bool operator()(const T* const x, T* residual) const {
    for (int r = 0; r < 6; ++r) {
      residual[r] = T(0);
      for (int c = 0; c < 6; ++c) residual[r] += S(r, c) * (x[c] - mean[c]);
    }
    return true;
  }
  Matrix6d S;
  Vector6d mean;
};

}  // namespace

RegularizedPoseEstimator::RegularizedPoseEstimator(const Eigen::Matrix3d& K, const RigidPose& T_AB,
                                                   PoseSolverOptions options)
    : K_(K), T_AB_(T_AB), options_(options) {}

PoseEstimate RegularizedPoseEstimator::estimateStandard(const PoseMeasurements& m,
                                                        const Vector6d& start) const {
  return solve(m, start, nullptr, nullptr, 0.0);
}

PoseEstimate RegularizedPoseEstimator::estimateRegularised(
    const PoseMeasurements& m, const Vector6d& xPred, const Matrix6d& omegaPred, double alpha,
    const std::optional<Vector6d>& start) const {
  return solve(m, start.value_or(xPred), &xPred, &omegaPred, alpha);
}

PoseEstimate RegularizedPoseEstimator::solve(const PoseMeasurements& m, const Vector6d& start,
                                             const Vector6d* xPred, const Matrix6d* omegaPred,
                                             double alpha) const {
  PoseEstimate result;
  double x[6];
  for (int i = 0; i < 6; ++i) x[i] = start[i];
  ceres::Problem::Options problemOptions;
  ceres::Problem problem(problemOptions);
  const auto loss = [&]() -> ceres::LossFunction* {
    return options_.huberScale > 0 ? new ceres::HuberLoss(options_.huberScale) : nullptr;
  };
  const RigidPose bToA = T_AB_.inverse();
  // The two symmetric distances of one match measure the same algebraic error, so together they
  // carry the information of one: each is weighted by half (sigma * sqrt 2), which keeps Omega a
  // consistent covariance (checked against the empirical scatter in the tests).
  const double symmetricPair = std::sqrt(2.0);
  if (options_.huberScale > 0) {
    // A robust loss acts per match, so each match gets its own residual block.
    for (const EpipolarMatch& e : m.toA)
      problem.AddResidualBlock(
          EpipolarDistanceCost::create(K_, RigidPose(), e.pRef, e.pK, e.sigma * symmetricPair),
          loss(), x);
    for (const EpipolarMatch& e : m.toB)
      problem.AddResidualBlock(
          EpipolarDistanceCost::create(K_, bToA, e.pRef, e.pK, e.sigma * symmetricPair), loss(), x);
    for (const ThreeViewMatch& t : m.threeView)
      problem.AddResidualBlock(
          ThreeViewReprojectionCost::create(K_, t.pointA, t.pK, t.whiteningOrScalar()), loss(), x);
  } else {
    // Plain least squares: one block per term (identical residuals, far less solver overhead).
    auto batch = [&](const std::vector<EpipolarMatch>& ms) {
      std::vector<EpipolarDistanceBatchCost::Match> out;
      for (const EpipolarMatch& e : ms)
        out.push_back({e.pRef, e.pK, 1.0 / (e.sigma * symmetricPair)});
      return out;
    };
    if (!m.toA.empty())
      problem.AddResidualBlock(EpipolarDistanceBatchCost::create(K_, RigidPose(), batch(m.toA)),
                               nullptr, x);
    if (!m.toB.empty())
      problem.AddResidualBlock(EpipolarDistanceBatchCost::create(K_, bToA, batch(m.toB)), nullptr,
                               x);
    if (!m.threeView.empty()) {
      std::vector<ThreeViewReprojectionBatchCost::Match> tv;
      for (const ThreeViewMatch& t : m.threeView)
        tv.push_back({t.pointA, t.pK, t.whiteningOrScalar()});
      problem.AddResidualBlock(ThreeViewReprojectionBatchCost::create(K_, std::move(tv)), nullptr,
                               x);
    }
  }
  if (xPred && omegaPred && alpha > 0) {
    const Eigen::LLT<Matrix6d> llt(omegaPred->inverse());
    if (llt.info() == Eigen::Success) {
      const Matrix6d S = std::sqrt(alpha) * Matrix6d(llt.matrixL()).transpose();
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<MotionPriorCost, 6, 6>(new MotionPriorCost(S, *xPred)),
          nullptr, x);
    }
  }
  if (problem.NumResidualBlocks() == 0) return result;

  ceres::Solver::Options options;
  // Six unknowns and hundreds of residuals: the normal equations are tiny and well conditioned
  // after whitening; measured ~2x faster than DENSE_QR here.
  options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  options.max_num_iterations = options_.maxIterations;
  options.num_threads = 1;
  options.minimizer_progress_to_stdout = false;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  for (int i = 0; i < 6; ++i) result.x[i] = x[i];
  result.finalCost = 2.0 * summary.final_cost;
  result.iterations = static_cast<int>(summary.iterations.size());
  result.converged = summary.termination_type == ceres::CONVERGENCE;

  // Omega = (J^T J)^-1 of the whitened residual vector at the solution.
  ceres::CRSMatrix J;
  ceres::Problem::EvaluateOptions evalOptions;
  evalOptions.apply_loss_function = false;
  problem.Evaluate(evalOptions, nullptr, nullptr, nullptr, &J);
  Matrix6d JtJ = Matrix6d::Zero();
  for (int r = 0; r < J.num_rows; ++r) {
    Vector6d row = Vector6d::Zero();
    for (int k = J.rows[r]; k < J.rows[r + 1]; ++k) row[J.cols[k]] = J.values[k];
    JtJ += row * row.transpose();
  }
  // Inverted after Jacobi scaling (unit diagonal): a strong prior makes JtJ's entries span many
  // orders of magnitude, and the unscaled factorisation then loses positivity to rounding.
  if (JtJ.allFinite() && JtJ.diagonal().minCoeff() > 0) {
    const Vector6d d = JtJ.diagonal().cwiseSqrt().cwiseInverse();
    const Matrix6d A = d.asDiagonal() * JtJ * d.asDiagonal();
    const Eigen::LLT<Matrix6d> llt(A);
    if (llt.info() == Eigen::Success) {
      result.covariance = d.asDiagonal() * llt.solve(Matrix6d::Identity()) * d.asDiagonal();
      result.covariance = 0.5 * (result.covariance + result.covariance.transpose());
      result.covarianceValid =
          result.covariance.allFinite() && result.covariance.diagonal().minCoeff() > 0;
    }
  }
  return result;
}

std::optional<Vector6d> RegularizedPoseEstimator::linearStart(
    const std::vector<ThreeViewMatch>& pairs) const {
  if (pairs.size() < 6) return std::nullopt;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (const ThreeViewMatch& p : pairs) {
    object.emplace_back(p.pointA.x(), p.pointA.y(), p.pointA.z());
    image.emplace_back(p.pK.x(), p.pK.y());
  }
  cv::Matx33d K;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) K(r, c) = K_(r, c);
  cv::Vec3d rvec, tvec;
  if (!cv::solvePnP(object, image, K, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_EPNP))
    return std::nullopt;
  cv::solvePnPRefineLM(object, image, K, cv::noArray(), rvec, tvec);
  Vector6d x;
  x << tvec[0], tvec[1], tvec[2], rvec[0], rvec[1], rvec[2];
  if (!x.allFinite()) return std::nullopt;
  return x;
}

}  // namespace reftrack
