#include "engine/matching/PatchAligner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "engine/core/Error.hpp"
#include "engine/features/SyntheticImages.hpp"

using namespace reftrack;

namespace {

// The target: the source through an affine map A (source -> target), with gain and offset.
struct Pair {
  cv::Mat source, target;
  cv::Matx33d A;
};

Pair affinePair(double angleDeg, double scale, cv::Point2d shift, double gain, double offset) {
  Pair p;
  p.source = test::texturedImage({240, 200}, 11);
  const double t = angleDeg * CV_PI / 180;
  p.A = cv::Matx33d(scale * std::cos(t), -scale * std::sin(t), shift.x, scale * std::sin(t),
                    scale * std::cos(t), shift.y, 0, 0, 1);
  cv::Mat warped = test::warpedBy(p.source, p.A);
  warped.convertTo(p.target, CV_8U, gain, offset);
  return p;
}

cv::Point2d apply(const cv::Matx33d& M, cv::Point2d q) {
  const cv::Vec3d v = M * cv::Vec3d(q.x, q.y, 1);
  return {v[0] / v[2], v[1] / v[2]};
}

}  // namespace

// The NCC-optimal position of the source window (around s, through J) in the target, by a dense
// search at 0.01 px steps within 0.5 px of `around` (cv::getRectSubPix + cv::matchTemplate): an
// independent reference for the aligner's result.
cv::Point2d nccPeak(const Pair& p, cv::Point2d s, const cv::Matx22d& J, cv::Point2d around) {
  cv::Mat T(15, 15, CV_32F), W;
  for (int v = 0; v < 15; ++v)
    for (int u = 0; u < 15; ++u) {
      const cv::Vec2d o = J * cv::Vec2d(u - 7, v - 7);
      cv::Mat px;
      cv::getRectSubPix(p.source, {1, 1},
                        cv::Point2f(static_cast<float>(s.x + o[0]), static_cast<float>(s.y + o[1])),
                        px, CV_32F);
      T.at<float>(v, u) = px.at<float>(0);
    }
  double best = -2;
  cv::Point2d peak = around;
  for (double dy = -0.5; dy <= 0.5; dy += 0.01)
    for (double dx = -0.5; dx <= 0.5; dx += 0.01) {
      const cv::Point2d q = around + cv::Point2d(dx, dy);
      cv::getRectSubPix(p.target, {15, 15}, cv::Point2f(q), W, CV_32F);
      cv::Mat r;
      cv::matchTemplate(W, T, r, cv::TM_CCOEFF_NORMED);
      if (r.at<float>(0) > best) {
        best = r.at<float>(0);
        peak = q;
      }
    }
  return peak;
}

// Sub-pixel accuracy under an exposure change (gain 0.7, offset 30), for a sub-pixel shift and
// under a rotation and a scale change with the exact local map J, from a start 1.6 px off: the
// aligned point is the NCC-optimal position of the source window (dense search; within 0.05 px for
// the shift, 0.15 px under the rotation and scale: the inverse-compositional fixed point ignores
// how the frame window's normalisation moves with the shift; measured up to 0.03 and 0.13 px), and
// lies within 0.3 px of where the warp puts the source point (cv::warpPerspective's
// bilinear resampling of a texture with sharp edges moves the optimum by up to 0.26 px here).
TEST(PatchAligner, FindsTheSourcePointInAnAffineTargetWithGainAndOffset) {
  struct Case {
    double angleDeg, scale, tolerance;
    cv::Point2d shift;
  };
  for (const Case c : {Case{0.0, 1.0, 0.05, {3.37, -2.61}}, Case{12.0, 1.15, 0.15, {-9.3, 6.7}}}) {
    const Pair p = affinePair(c.angleDeg, c.scale, c.shift, 0.7, 30.0);
    const cv::Matx22d J = cv::Matx22d(p.A(0, 0), p.A(0, 1), p.A(1, 0), p.A(1, 1)).inv();
    const PatchAligner aligner;
    int aligned = 0;
    for (const cv::Point2d s :
         {cv::Point2d(80, 70), cv::Point2d(120, 100), cv::Point2d(150, 130), cv::Point2d(100, 140),
          cv::Point2d(60, 110), cv::Point2d(170, 80)}) {
      const cv::Point2d truth = apply(p.A, s);
      const cv::Point2d start = truth + cv::Point2d(1.3, -0.9);  // e.g. a detected corner nearby
      const std::optional<PatchAlignment> a = aligner.align(p.source, s, J, p.target, start);
      if (!a) continue;  // a window without a position (flat, or a single edge)
      ++aligned;
      const cv::Point2d peak = nccPeak(p, s, J, truth);
      EXPECT_NEAR(a->position.x, peak.x, c.tolerance) << c.angleDeg;
      EXPECT_NEAR(a->position.y, peak.y, c.tolerance) << c.angleDeg;
      EXPECT_NEAR(a->position.x, truth.x, 0.3) << c.angleDeg;
      EXPECT_NEAR(a->position.y, truth.y, 0.3) << c.angleDeg;
      EXPECT_GT(a->score, 0.85);  // two resamplings of sharp edges, magnified (measured >= 0.888)
      EXPECT_LT(a->sigmaPx, 0.2);
    }
    EXPECT_GE(aligned, 3) << c.angleDeg;
  }
}

// Bilinear sample in double precision (the test's own, independent of the aligner's).
double sampleAt(const cv::Mat& image, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double ax = x - x0, ay = y - y0;
  const auto at = [&](int u, int v) { return static_cast<double>(image.at<uchar>(v, u)); };
  return (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x0 + 1, y0)) +
         ay * ((1 - ax) * at(x0, y0 + 1) + ax * at(x0 + 1, y0 + 1));
}

// The score and the SD the aligner reports (it works on sums of the windows, never normalising
// them) are those of the windows themselves at the aligned position, recomputed here directly:
// the NCC of the template and the target window, and sigma^2 = SSE / (N - 2) * trace((G^T G)^-1)
// / 2 from the normalised windows' residuals and the template's central-difference gradients.
// Tolerances: float sums of 81-225 samples against doubles: the score within 3e-4 (measured up to
// 1.1e-4), the SD within 1e-4 px plus 0.1% (the SSE is a difference of sums, which loses relative
// precision where the windows nearly agree: measured 1.6e-5 px at an SD of 0.009 px).
TEST(PatchAligner, ScoreAndSigmaAreThoseOfTheAlignedWindows) {
  const Pair p = affinePair(12.0, 1.15, {-9.3, 6.7}, 0.7, 30.0);
  const cv::Matx22d J = cv::Matx22d(p.A(0, 0), p.A(0, 1), p.A(1, 0), p.A(1, 1)).inv();
  for (const int n : {4, 7}) {
    PatchAlignerParams params;
    params.halfWindow = n;
    const PatchAligner aligner(params);
    int checked = 0;
    std::vector<cv::Point2d> sources;  // a grid over the texture
    for (int y = 50; y <= 150; y += 20)
      for (int x = 50; x <= 190; x += 20) sources.emplace_back(x, y);
    for (const cv::Point2d s : sources) {
      const cv::Point2d start = apply(p.A, s) + cv::Point2d(0.8, -0.6);
      const std::optional<PatchAlignment> a = aligner.align(p.source, s, J, p.target, start);
      if (!a) continue;
      ++checked;
      // The bordered template and the target window at the aligned position.
      const int side = 2 * n + 1, border = side + 2, count = side * side;
      std::vector<double> T(static_cast<std::size_t>(border * border)), W;
      for (int v = 0; v < border; ++v)
        for (int u = 0; u < border; ++u) {
          const cv::Vec2d o = J * cv::Vec2d(u - n - 1, v - n - 1);
          T[static_cast<std::size_t>(v * border + u)] = sampleAt(p.source, s.x + o[0], s.y + o[1]);
        }
      for (int v = -n; v <= n; ++v)
        for (int u = -n; u <= n; ++u)
          W.push_back(sampleAt(p.target, a->position.x + u, a->position.y + v));
      // Normalised with the inner window's mean and SD (population), as the contract says.
      const auto normalise = [count](const std::vector<double>& inner, double& mean, double& sd) {
        double sum = 0, sum2 = 0;
        for (double x : inner) {
          sum += x;
          sum2 += x * x;
        }
        mean = sum / count;
        sd = std::sqrt(sum2 / count - mean * mean);
      };
      std::vector<double> inner;
      for (int v = 1; v <= side; ++v)
        for (int u = 1; u <= side; ++u)
          inner.push_back(T[static_cast<std::size_t>(v * border + u)]);
      double mT = 0, sT = 0, mW = 0, sW = 0;
      normalise(inner, mT, sT);
      normalise(W, mW, sW);
      double dot = 0, sse = 0, gxx = 0, gxy = 0, gyy = 0;
      for (int v = 0; v < side; ++v)
        for (int u = 0; u < side; ++u) {
          const auto at = [&](int du, int dv) {
            return (T[static_cast<std::size_t>((v + 1 + dv) * border + u + 1 + du)] - mT) / sT;
          };
          const double t = at(0, 0);
          const double w = (W[static_cast<std::size_t>(v * side + u)] - mW) / sW;
          const double gx = 0.5 * (at(1, 0) - at(-1, 0)), gy = 0.5 * (at(0, 1) - at(0, -1));
          dot += t * w;
          sse += (t - w) * (t - w);
          gxx += gx * gx;
          gxy += gx * gy;
          gyy += gy * gy;
        }
      const double sigma =
          std::sqrt(0.5 * sse / (count - 2) * (gxx + gyy) / (gxx * gyy - gxy * gxy));
      EXPECT_NEAR(a->score, dot / count, 3e-4) << "n " << n << " at " << s;
      EXPECT_NEAR(a->sigmaPx, sigma, 1e-4 + 1e-3 * sigma) << "n " << n << " at " << s;
    }
    EXPECT_GE(checked, 10) << "n " << n;
  }
}

TEST(PatchAligner, RefusesFlatTemplatesDriftAndLeavingTheImage) {
  const Pair p = affinePair(0.0, 1.0, {0, 0}, 1.0, 0.0);
  const PatchAligner aligner;
  const cv::Matx22d I(1, 0, 0, 1);
  // Flat: a uniform source.
  const cv::Mat flat(200, 200, CV_8UC1, cv::Scalar(128));
  EXPECT_FALSE(aligner.align(flat, {100, 100}, I, p.target, {100, 100}));
  // The template leaves the source; the start leaves the target.
  EXPECT_FALSE(aligner.align(p.source, {2, 2}, I, p.target, {100, 100}));
  EXPECT_FALSE(aligner.align(p.source, {100, 100}, I, p.target, {-50, 100}));
  EXPECT_FALSE(aligner.align(p.source, {NAN, 100}, I, p.target, {100, 100}));
  // Another place of the texture: it either moves beyond max_shift_px or correlates poorly.
  EXPECT_FALSE(aligner.align(p.source, {100, 100}, I, p.target, {160, 60}));
  // Bad inputs and parameters.
  EXPECT_THROW(aligner.align(cv::Mat(10, 10, CV_32F), {5, 5}, I, p.target, {5, 5}), Error);
  PatchAlignerParams bad;
  bad.halfWindow = 0;
  EXPECT_THROW(PatchAligner{bad}, Error);
}
