#include "engine/estimation/ReprojectionRefiner.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>

namespace reftrack {
namespace {

Eigen::Matrix3d rotationOf(const cv::Vec3d& rvec) {
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  Eigen::Matrix3d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = R(r, c);
  return out;
}

// The squared reprojection error, and (when H, g are given) the Gauss-Newton system of the
// update [dw, dt]: X_c(d) = exp([dw]x) R X + t + dt.
double squaredError(const std::vector<cv::Point3d>& object, const std::vector<cv::Point2d>& image,
                    const cv::Matx33d& K, const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                    Eigen::Matrix<double, 6, 6>* H, Eigen::Matrix<double, 6, 1>* g, int* used) {
  double sum = 0.0;
  int n = 0;
  if (H) H->setZero();
  if (g) g->setZero();
  for (std::size_t i = 0; i < object.size(); ++i) {
    const Eigen::Vector3d RX = R * Eigen::Vector3d(object[i].x, object[i].y, object[i].z);
    const Eigen::Vector3d Xc = RX + t;
    if (!(Xc.z() > 1e-9)) continue;
    const double iz = 1.0 / Xc.z();
    const double u = (K(0, 0) * Xc.x() + K(0, 1) * Xc.y()) * iz + K(0, 2);
    const double v = K(1, 1) * Xc.y() * iz + K(1, 2);
    const Eigen::Vector2d r(u - image[i].x, v - image[i].y);
    sum += r.squaredNorm();
    ++n;
    if (!H) continue;
    Eigen::Matrix<double, 2, 3> dPdX;
    dPdX << K(0, 0) * iz, K(0, 1) * iz, -(K(0, 0) * Xc.x() + K(0, 1) * Xc.y()) * iz * iz, 0.0,
        K(1, 1) * iz, -K(1, 1) * Xc.y() * iz * iz;
    Eigen::Matrix3d skew;  // d(dw x RX)/d(dw) = -[RX]x
    skew << 0.0, RX.z(), -RX.y(), -RX.z(), 0.0, RX.x(), RX.y(), -RX.x(), 0.0;
    Eigen::Matrix<double, 2, 6> J;
    J.leftCols<3>() = dPdX * skew;
    J.rightCols<3>() = dPdX;
    *H += J.transpose() * J;
    *g += J.transpose() * r;
  }
  if (used) *used = n;
  return sum;
}

}  // namespace

int refineReprojection(const std::vector<cv::Point3d>& object,
                       const std::vector<cv::Point2d>& image, const cv::Matx33d& K, cv::Vec3d& rvec,
                       cv::Vec3d& tvec, int maxIterations) {
  if (object.size() != image.size() || object.size() < 3) return 0;
  Eigen::Matrix3d R = rotationOf(rvec);
  Eigen::Vector3d t(tvec[0], tvec[1], tvec[2]);
  int steps = 0;
  // Gauss-Newton, damped (Levenberg) only when a full step does not lower the error: from a
  // RANSAC or SQPnP start the undamped step almost always does.
  double lambda = 0.0;
  for (int it = 0; it < maxIterations; ++it) {
    Eigen::Matrix<double, 6, 6> H;
    Eigen::Matrix<double, 6, 1> g;
    int used = 0;
    const double before = squaredError(object, image, K, R, t, &H, &g, &used);
    if (used < 3) break;
    bool stepped = false;
    double after = before;
    for (int attempt = 0; attempt < 6 && !stepped; ++attempt) {
      Eigen::Matrix<double, 6, 6> A = H;
      A.diagonal() += lambda * H.diagonal();
      const Eigen::Matrix<double, 6, 1> d = A.ldlt().solve(-g);
      if (!d.allFinite()) break;
      const double angle = d.head<3>().norm();
      const Eigen::Matrix3d dR =
          angle > 0.0 ? Eigen::AngleAxisd(angle, d.head<3>() / angle).toRotationMatrix()
                      : Eigen::Matrix3d::Identity();
      const Eigen::Matrix3d R1 = dR * R;
      const Eigen::Vector3d t1 = t + d.tail<3>();
      after = squaredError(object, image, K, R1, t1, nullptr, nullptr, nullptr);
      if (after < before) {
        R = R1;
        t = t1;
        stepped = true;
        lambda *= 0.1;
      } else {
        lambda = lambda == 0.0 ? 1e-3 : lambda * 10.0;
      }
    }
    if (!stepped) break;
    ++steps;
    // Converged when a step gains less than a part in 1e10 of the error: further steps only
    // chase rounding (on the desk clip's refits, 2-3 steps instead of the full 10).
    if (before - after <= 1e-10 * before) break;
  }
  if (steps > 0) {
    cv::Matx33d Rcv;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) Rcv(r, c) = R(r, c);
    cv::Rodrigues(Rcv, rvec);
    tvec = cv::Vec3d(t.x(), t.y(), t.z());
  }
  return steps;
}

}  // namespace reftrack
