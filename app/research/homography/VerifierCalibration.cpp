#include "app/research/homography/VerifierCalibration.hpp"

#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "app/simulator/SensorNoise.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/ImagePyramid.hpp"

namespace reftrack::app {

cv::Matx33d displacedHomography(const cv::Matx33d& H, cv::Size size,
                                const std::vector<cv::Point2d>& offsets) {
  if (offsets.size() != 4) throw Error("displaced homography: four corner offsets are needed");
  const double w = size.width - 1.0, h = size.height - 1.0;
  const std::vector<cv::Point2f> corners = {
      {0, 0}, {float(w), 0}, {float(w), float(h)}, {0, float(h)}};
  std::vector<cv::Point2f> moved;
  for (size_t i = 0; i < 4; ++i)
    moved.emplace_back(corners[i].x + static_cast<float>(offsets[i].x),
                       corners[i].y + static_cast<float>(offsets[i].y));
  const cv::Matx33d D(cv::getPerspectiveTransform(corners, moved));
  cv::Matx33d out = D * H;
  return out * (1.0 / out(2, 2));
}

std::vector<VerifierPairResult> runVerifierCalibration(const std::vector<HomographyPair>& pairs,
                                                       const std::vector<double>& offsets,
                                                       int trials, std::uint64_t seed,
                                                       const RegistrationCheckParams& params) {
  if (trials < 1) throw Error("verifier calibration: trials must be at least 1");
  std::vector<VerifierPairResult> out;
  std::optional<RegistrationVerifier> verifier;
  const cv::Mat* reference = nullptr;
  std::uint64_t n = 0;
  for (const HomographyPair& p : pairs) {
    if (reference == nullptr || reference->data != p.reference.data) {
      verifier.emplace(p.reference, params);
      reference = &p.reference;
    }
    const ImagePyramid frame(p.frame);
    VerifierPairResult r;
    const auto record = [&](double offset, const cv::Matx33d& H) {
      const RegistrationCheck c = verifier->check(frame, H);
      r.outcomes.push_back(
          {offset, c.passed, c.measurable, c.confirmed, c.spread, c.offsetPx, c.failure});
    };
    record(0.0, p.truth);
    for (double d : offsets) {
      for (int t = 0; t < trials; ++t) {
        cv::RNG rng(mixSeed(seed, ++n));
        std::vector<cv::Point2d> moves;
        for (int k = 0; k < 4; ++k) {
          const double a = rng.uniform(0.0, 2.0 * std::numbers::pi);
          moves.emplace_back(d * std::cos(a), d * std::sin(a));
        }
        record(d, displacedHomography(p.truth, p.frame.size(), moves));
      }
    }
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace reftrack::app
