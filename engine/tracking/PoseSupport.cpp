#include "engine/tracking/PoseSupport.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <vector>

namespace reftrack {

std::optional<double> reprojectionSupportSdPx(const PinholeCamera& camera, const RigidPose& T,
                                              std::span<const ThreeViewMatch> support) {
  const std::size_t n = support.size();
  if (n < 4) return std::nullopt;
  const Vector6d x = T.toVector6();
  // Central differences: the projection is smooth and the step far above rounding.
  constexpr double kStep = 1e-6;
  std::vector<Eigen::Matrix<double, 2, 6>> J(n);
  for (int i = 0; i < 6; ++i) {
    Vector6d plus = x, minus = x;
    plus[i] += kStep;
    minus[i] -= kStep;
    const RigidPose Tp = RigidPose::fromVector6(plus), Tm = RigidPose::fromVector6(minus);
    for (std::size_t k = 0; k < n; ++k)
      J[k].col(i) =
          (camera.project(Tp * support[k].pointA) - camera.project(Tm * support[k].pointA)) /
          (2.0 * kStep);
  }
  Matrix6d JtJ = Matrix6d::Zero();
  double sse = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    JtJ += J[k].transpose() * J[k];
    sse += (camera.project(T * support[k].pointA) - support[k].pK).squaredNorm();
  }
  // Jacobi scaling before the factorisation: translation and rotation columns differ in units.
  const Vector6d d = JtJ.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const Eigen::LLT<Matrix6d> llt(d.asDiagonal() * JtJ * d.asDiagonal());
  if (llt.info() != Eigen::Success) return std::nullopt;
  const Matrix6d covariance = (sse / static_cast<double>(2 * n - 6)) * d.asDiagonal() *
                              llt.solve(Matrix6d::Identity()) * d.asDiagonal();
  double variance = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    variance += (J[k] * covariance * J[k].transpose()).trace() / 2.0;
  const double sd = std::sqrt(variance / static_cast<double>(n));
  if (!std::isfinite(sd)) return std::nullopt;
  return sd;
}

}  // namespace reftrack
