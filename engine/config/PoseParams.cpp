#include "engine/config/PoseParams.hpp"

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

std::string toString(PoseEstimatorKind kind) {
  return kind == PoseEstimatorKind::Standard ? "standard" : "regularised";
}

PoseEstimatorKind parsePoseEstimatorKind(const std::string& text) {
  if (text == "standard") return PoseEstimatorKind::Standard;
  if (text == "regularised" || text == "regularized") return PoseEstimatorKind::Regularised;
  throw Error("parameter 'pose.estimator' must be 'standard' or 'regularised', got '" + text + "'");
}

void PoseParams::check() const {
  requireFiniteInRange("pose.alpha", alpha, 0.0, 1e12);
  requireIntInRange("pose.ar_order", arOrder, 1, 10);
  requireFiniteInRange("pose.translation_sigma", translationSigma, 1e-12, 1e6);
  requireFiniteInRange("pose.rotation_sigma", rotationSigma, 1e-12, 1e3);
  requireFiniteInRange("pose.rolling_shutter_readout", rollingShutterReadout, 0.0, 1.0);
}

void PoseParams::write(cv::FileStorage& fs) const {
  fs << "estimator" << toString(estimator) << "alpha" << alpha << "ar_order" << arOrder
     << "translation_sigma" << translationSigma << "rotation_sigma" << rotationSigma
     << "motion_model_file" << motionModelFile << "rolling_shutter_readout"
     << rollingShutterReadout;
}

void PoseParams::read(const cv::FileNode& node) {
  const std::string s = "pose";
  requireKeysWrittenBy(node, s, [](cv::FileStorage& fs) { PoseParams{}.write(fs); });
  std::string estimatorName = toString(estimator);
  readConfigValue(node, s, "estimator", estimatorName);
  estimator = parsePoseEstimatorKind(estimatorName);
  readConfigValue(node, s, "alpha", alpha);
  readConfigValue(node, s, "ar_order", arOrder);
  readConfigValue(node, s, "translation_sigma", translationSigma);
  readConfigValue(node, s, "rotation_sigma", rotationSigma);
  readConfigValue(node, s, "motion_model_file", motionModelFile);
  readConfigValue(node, s, "rolling_shutter_readout", rollingShutterReadout);
  check();
}

}  // namespace reftrack
