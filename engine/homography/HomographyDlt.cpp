#include "engine/homography/HomographyDlt.hpp"

#include <Eigen/Eigenvalues>
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

cv::Point2d transferPoint(const cv::Matx33d& H, cv::Point2d p) {
  const double w = H(2, 0) * p.x + H(2, 1) * p.y + H(2, 2);
  return {(H(0, 0) * p.x + H(0, 1) * p.y + H(0, 2)) / w,
          (H(1, 0) * p.x + H(1, 1) * p.y + H(1, 2)) / w};
}

double transferError(const cv::Matx33d& H, cv::Point2f src, cv::Point2f dst) {
  const cv::Point2d q = transferPoint(H, cv::Point2d(src.x, src.y));
  return std::hypot(q.x - dst.x, q.y - dst.y);
}

}  // namespace reftrack
