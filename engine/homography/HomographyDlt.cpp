#include "engine/homography/HomographyDlt.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace reftrack {

namespace {

template <class F>
void forEachIndex(size_t n, const std::vector<int>& indices, F f) {
  if (indices.empty())
    for (size_t i = 0; i < n; ++i) f(static_cast<int>(i));
  else
    for (int i : indices) f(i);
}

}  // namespace

cv::Matx33d normalisingTransform(const std::vector<cv::Point2f>& points,
                                 const std::vector<int>& indices) {
  double cx = 0, cy = 0;
  int n = 0;
  forEachIndex(points.size(), indices, [&](int i) {
    cx += points[static_cast<size_t>(i)].x;
    cy += points[static_cast<size_t>(i)].y;
    ++n;
  });
  if (n == 0) return cv::Matx33d::eye();
  cx /= n;
  cy /= n;
  double meanDist = 0;
  forEachIndex(points.size(), indices, [&](int i) {
    meanDist +=
        std::hypot(points[static_cast<size_t>(i)].x - cx, points[static_cast<size_t>(i)].y - cy);
  });
  meanDist /= n;
  const double s = meanDist > 1e-12 ? std::sqrt(2.0) / meanDist : 1.0;
  return cv::Matx33d(s, 0, -s * cx, 0, s, -s * cy, 0, 0, 1);
}

std::optional<cv::Matx33d> homographyDlt(const std::vector<cv::Point2f>& src,
                                         const std::vector<cv::Point2f>& dst,
                                         const std::vector<int>& indices) {
  if (src.size() != dst.size()) return std::nullopt;
  const size_t n = indices.empty() ? src.size() : indices.size();
  if (n < 4) return std::nullopt;
  bool finite = true;
  forEachIndex(src.size(), indices, [&](int i) {
    const auto& a = src[static_cast<size_t>(i)];
    const auto& b = dst[static_cast<size_t>(i)];
    finite = finite && std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(b.x) &&
             std::isfinite(b.y);
  });
  if (!finite) return std::nullopt;
  const cv::Matx33d T1 = normalisingTransform(src, indices);
  const cv::Matx33d T2 = normalisingTransform(dst, indices);
  // Normal equations A^T A of the 2n x 9 DLT system; its eigenvector of the smallest eigenvalue
  // is the least-squares solution (well conditioned after the normalisation).
  Eigen::Matrix<double, 9, 9> AtA = Eigen::Matrix<double, 9, 9>::Zero();
  forEachIndex(src.size(), indices, [&](int i) {
    const auto& a = src[static_cast<size_t>(i)];
    const auto& b = dst[static_cast<size_t>(i)];
    const double x = T1(0, 0) * a.x + T1(0, 2), y = T1(1, 1) * a.y + T1(1, 2);
    const double u = T2(0, 0) * b.x + T2(0, 2), v = T2(1, 1) * b.y + T2(1, 2);
    Eigen::Matrix<double, 9, 1> r1, r2;
    r1 << 0, 0, 0, -x, -y, -1, v * x, v * y, v;
    r2 << x, y, 1, 0, 0, 0, -u * x, -u * y, -u;
    AtA.selfadjointView<Eigen::Lower>().rankUpdate(r1);
    AtA.selfadjointView<Eigen::Lower>().rankUpdate(r2);
  });
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eig(
      AtA.selfadjointView<Eigen::Lower>());
  if (eig.info() != Eigen::Success) return std::nullopt;
  const Eigen::Matrix<double, 9, 1> evals = eig.eigenvalues();
  // A second (near-)zero eigenvalue: the points do not fix H (e.g. three collinear).
  if (evals(1) <= 1e-10 * std::max(1.0, evals(8))) return std::nullopt;
  const Eigen::Matrix<double, 9, 1> h = eig.eigenvectors().col(0);
  cv::Matx33d Hn(h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8));
  cv::Matx33d H = T2.inv() * Hn * T1;
  const double norm = cv::norm(H);
  if (!(norm > 0) || !std::isfinite(norm)) return std::nullopt;
  H *= std::abs(H(2, 2)) > 1e-9 * norm ? 1.0 / H(2, 2) : 1.0 / norm;
  return H;
}

namespace {

// Twice the area of triangle abc over the squared length of its longest side: ~0 when collinear.
double triangleShape(cv::Point2d a, cv::Point2d b, cv::Point2d c) {
  const cv::Point2d ab = b - a, ac = c - a, bc = c - b;
  const double longest = std::max({ab.dot(ab), ac.dot(ac), bc.dot(bc)});
  return longest > 0 ? std::abs(ab.x * ac.y - ab.y * ac.x) / longest : 0.0;
}

bool nearlyCollinear(const cv::Point2d p[4]) {
  // A triangle flatter than ~0.6 degrees at its widest angle leaves H badly determined.
  constexpr double kMinShape = 0.01;
  return triangleShape(p[0], p[1], p[2]) < kMinShape ||
         triangleShape(p[0], p[1], p[3]) < kMinShape ||
         triangleShape(p[0], p[2], p[3]) < kMinShape || triangleShape(p[1], p[2], p[3]) < kMinShape;
}

}  // namespace

std::optional<cv::Matx33d> homographyFromFourPoints(const std::vector<cv::Point2f>& src,
                                                    const std::vector<cv::Point2f>& dst,
                                                    const int sample[4]) {
  cv::Point2d a[4], b[4];
  for (int k = 0; k < 4; ++k) {
    const size_t i = static_cast<size_t>(sample[k]);
    if (i >= src.size() || i >= dst.size()) return std::nullopt;
    a[k] = cv::Point2d(src[i].x, src[i].y);
    b[k] = cv::Point2d(dst[i].x, dst[i].y);
    if (!std::isfinite(a[k].x) || !std::isfinite(a[k].y) || !std::isfinite(b[k].x) ||
        !std::isfinite(b[k].y))
      return std::nullopt;
  }
  if (nearlyCollinear(a) || nearlyCollinear(b)) return std::nullopt;
  // Normalise each set (centroid to the origin, mean distance sqrt(2)) for conditioning.
  const auto normalise = [](cv::Point2d p[4]) {
    const cv::Point2d c = (p[0] + p[1] + p[2] + p[3]) * 0.25;
    double d = 0;
    for (int k = 0; k < 4; ++k) d += std::hypot(p[k].x - c.x, p[k].y - c.y);
    const double s = d > 1e-12 ? 4.0 * std::sqrt(2.0) / d : 1.0;
    for (int k = 0; k < 4; ++k) p[k] = (p[k] - c) * s;
    return cv::Matx33d(s, 0, -s * c.x, 0, s, -s * c.y, 0, 0, 1);
  };
  const cv::Matx33d T1 = normalise(a), T2 = normalise(b);
  Eigen::Matrix<double, 8, 8> A;
  Eigen::Matrix<double, 8, 1> rhs;
  for (int k = 0; k < 4; ++k) {
    const double x = a[k].x, y = a[k].y, u = b[k].x, v = b[k].y;
    A.row(2 * k) << x, y, 1, 0, 0, 0, -u * x, -u * y;
    A.row(2 * k + 1) << 0, 0, 0, x, y, 1, -v * x, -v * y;
    rhs(2 * k) = u;
    rhs(2 * k + 1) = v;
  }
  const Eigen::PartialPivLU<Eigen::Matrix<double, 8, 8>> lu(A);
  if (!(std::abs(lu.determinant()) > 1e-12)) return std::nullopt;
  const Eigen::Matrix<double, 8, 1> h = lu.solve(rhs);
  const cv::Matx33d Hn(h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), 1.0);
  cv::Matx33d H = T2.inv() * Hn * T1;
  if (!(std::abs(H(2, 2)) > 1e-12)) return std::nullopt;
  H *= 1.0 / H(2, 2);
  for (int k = 0; k < 9; ++k)
    if (!std::isfinite(H.val[k])) return std::nullopt;
  return H;
}

cv::Point2d transferPoint(const cv::Matx33d& H, cv::Point2d p) {
  const double w = H(2, 0) * p.x + H(2, 1) * p.y + H(2, 2);
  return {(H(0, 0) * p.x + H(0, 1) * p.y + H(0, 2)) / w,
          (H(1, 0) * p.x + H(1, 1) * p.y + H(1, 2)) / w};
}

cv::Matx22d transferJacobian(const cv::Matx33d& H, cv::Point2d p) {
  const double w = H(2, 0) * p.x + H(2, 1) * p.y + H(2, 2);
  const double u = (H(0, 0) * p.x + H(0, 1) * p.y + H(0, 2)) / w;
  const double v = (H(1, 0) * p.x + H(1, 1) * p.y + H(1, 2)) / w;
  return cv::Matx22d((H(0, 0) - u * H(2, 0)) / w, (H(0, 1) - u * H(2, 1)) / w,
                     (H(1, 0) - v * H(2, 0)) / w, (H(1, 1) - v * H(2, 1)) / w);
}

double transferError(const cv::Matx33d& H, cv::Point2f src, cv::Point2f dst) {
  const cv::Point2d q = transferPoint(H, cv::Point2d(src.x, src.y));
  return std::hypot(q.x - dst.x, q.y - dst.y);
}

}  // namespace reftrack
