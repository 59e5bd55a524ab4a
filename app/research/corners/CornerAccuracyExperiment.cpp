#include "app/research/corners/CornerAccuracyExperiment.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

#include "engine/features/CornerDetector.hpp"
#include "engine/features/RmsContrast.hpp"

namespace reftrack::app {

namespace {

// Fraction of pixel [x-0.5, x+0.5] to the right of the edge at e.
double coverage(double x, double e) { return std::clamp(x + 0.5 - e, 0.0, 1.0); }

// Dark background, bright quadrant x > x0 and y > y0 (the corner at (x0, y0)), exact coverage.
cv::Mat idealCorner(int side, double x0, double y0, double dark, double amplitude) {
  cv::Mat img(side, side, CV_64F);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      img.at<double>(y, x) = dark + amplitude * coverage(x, x0) * coverage(y, y0);
  return img;
}

}  // namespace

CornerAccuracyResult runCornerAccuracyExperiment(const CornerAccuracyOptions& options) {
  CornerAccuracyResult result;
  cv::RNG rng(options.seed);
  const int side = 48;
  CornerParams params = options.corners;
  params.detectAtPaperScale = false;  // one small image: detect at full resolution
  const CornerDetector detector(params);
  std::vector<double> fitContrast, fitVariance;
  for (double amplitude : options.amplitudes) {
    CornerAccuracyRow row;
    row.amplitude = amplitude;
    double sx = 0, sy = 0, sxx = 0, syy = 0, contrastSum = 0;
    int found = 0;
    for (int trial = 0; trial < options.trialsPerAmplitude; ++trial) {
      const double x0 = side / 2.0 + rng.uniform(-0.5, 0.5);
      const double y0 = side / 2.0 + rng.uniform(-0.5, 0.5);
      const double dark = 128.0 - amplitude / 2.0;
      cv::Mat img = idealCorner(side, x0, y0, dark, amplitude);
      cv::Mat noise(img.size(), CV_64F);
      rng.fill(noise, cv::RNG::NORMAL, 0.0, options.noiseSigma);
      img += noise;
      cv::Mat gray;
      img.convertTo(gray, CV_8U);  // rounds and saturates like a camera
      // Pixel x covers [x - 0.5, x + 0.5] (pixel-centre convention), so the edges lie exactly at
      // x0 and y0.
      const cv::Point2f truth(static_cast<float>(x0), static_cast<float>(y0));
      contrastSum += rmsContrast(gray, truth, params.contrastWindow);
      double best = 2.0;
      cv::Point2f bestP;
      for (const Corner& c : detector.detect(gray)) {
        const double d = cv::norm(c.position - truth);
        if (d < best) {
          best = d;
          bestP = c.position;
        }
      }
      if (best >= 2.0) continue;
      ++found;
      const double ex = bestP.x - truth.x, ey = bestP.y - truth.y;
      sx += ex;
      sy += ey;
      sxx += ex * ex;
      syy += ey * ey;
    }
    row.rmsContrast = contrastSum / options.trialsPerAmplitude;
    row.detectionRate = static_cast<double>(found) / options.trialsPerAmplitude;
    if (found >= 2) {
      const double mx = sx / found, my = sy / found;
      row.variancePx2 = 0.5 * ((sxx / found - mx * mx) + (syy / found - my * my));
      row.biasPx = std::hypot(mx, my);
      if (row.detectionRate > 0.5) {
        fitContrast.push_back(row.rmsContrast);
        fitVariance.push_back(row.variancePx2);
      }
    }
    result.rows.push_back(row);
  }
  if (fitContrast.size() >= 2) result.fitted = CornerVarianceModel::fit(fitContrast, fitVariance);
  return result;
}

}  // namespace reftrack::app
