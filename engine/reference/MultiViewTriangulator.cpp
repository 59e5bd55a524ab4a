#include "engine/reference/MultiViewTriangulator.hpp"

#include <ceres/ceres.h>

#include <Eigen/SVD>
#include <cmath>
#include <limits>

#include "engine/reference/TwoViewTriangulator.hpp"

namespace reftrack {

Eigen::Vector3d MultiViewTriangulator::linear(const std::vector<PosedPixel>& views) const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (views.size() < 2) return Eigen::Vector3d::Constant(nan);
  Eigen::MatrixXd A(2 * views.size(), 4);
  for (std::size_t i = 0; i < views.size(); ++i) {
    Eigen::Matrix<double, 3, 4> P;
    P.leftCols<3>() = K_ * views[i].worldToCamera.rotation();
    P.col(3) = K_ * views[i].worldToCamera.translation();
    const Eigen::Vector2d& p = views[i].pixel;
    A.row(static_cast<Eigen::Index>(2 * i)) = p.x() * P.row(2) - P.row(0);
    A.row(static_cast<Eigen::Index>(2 * i + 1)) = p.y() * P.row(2) - P.row(1);
  }
  // Rows are scaled alike (pixels); the smallest right singular vector is the homogeneous point.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d X = svd.matrixV().col(3);
  if (std::abs(X.w()) < 1e-12) return Eigen::Vector3d::Constant(nan);
  return X.head<3>() / X.w();
}

Eigen::Vector3d MultiViewTriangulator::refine(const std::vector<PosedPixel>& views,
                                              const Eigen::Vector3d& initial) const {
  double X[3] = {initial.x(), initial.y(), initial.z()};
  ceres::Problem problem;
  for (const PosedPixel& v : views)
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PointReprojectionCost, 2, 3>(
                                 new PointReprojectionCost(K_, v.worldToCamera, v.pixel)),
                             nullptr, X);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 20;
  options.function_tolerance = 1e-12;
  options.parameter_tolerance = 1e-12;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return {X[0], X[1], X[2]};
}

double MultiViewTriangulator::reprojectionError(const PosedPixel& view,
                                                const Eigen::Vector3d& X) const {
  const Eigen::Vector3d q = K_ * (view.worldToCamera * X);
  if (!(q.z() > 0.0)) return std::numeric_limits<double>::infinity();
  return (q.head<2>() / q.z() - view.pixel).norm();
}

}  // namespace reftrack
