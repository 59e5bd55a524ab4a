#include "engine/estimation/MotionModelFile.hpp"

#include <cmath>
#include <opencv2/core.hpp>

#include "engine/config/ConfigFile.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/config/YamlMatrix.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

cv::Mat toMat(const Eigen::MatrixXd& m) {
  cv::Mat out(static_cast<int>(m.rows()), static_cast<int>(m.cols()), CV_64F);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c) out.at<double>(r, c) = m(r, c);
  return out;
}

FittedMotionModel readMotionModel(const YamlNode& root) {
  requireKnownKeys(root, {"kind", "order", "weights", "Q", "explained_variance",
                          "source_trajectory", "frame_count"});
  const auto node = [&](const char* key) {
    const YamlNode n = root[key];
    if (!n.present()) throw Error(std::string("missing key '") + key + "'");
    return n;
  };
  const auto matrix = [&](const char* key, int rows, int cols) {
    const YamlNode n = node(key);
    const std::string quoted = std::string("'") + key + "'";
    cv::Mat m = readYamlMatrix(n);
    if (m.rows != rows || m.cols != cols || m.channels() != 1)
      n.fail(quoted + " must be " + std::to_string(rows) + "x" + std::to_string(cols) + ", got " +
             std::to_string(m.rows) + "x" + std::to_string(m.cols));
    m.convertTo(m, CV_64F);
    if (!cv::checkRange(m)) n.fail(quoted + " contains NaN or infinity");
    return m;
  };

  FittedMotionModel out;
  const YamlNode kind = node("kind");
  const std::string kindText = kind.text().value_or("");
  if (kindText != "ar" && kindText != "random_walk")
    kind.fail("'kind' must be \"ar\" or \"random_walk\"");
  out.randomWalk = kindText == "random_walk";
  const YamlNode orderNode = node("order");
  const int p = orderNode.integer().value_or(0);
  if (p < 1 || p > 100) orderNode.fail("'order' must be an integer from 1 to 100");
  const cv::Mat w = matrix("weights", p, 6), q = matrix("Q", 6, 6),
                ev = matrix("explained_variance", 1, 6);
  std::vector<Vector6d> weights(p);
  for (int j = 0; j < p; ++j)
    for (int c = 0; c < 6; ++c) weights[j][c] = w.at<double>(j, c);
  Matrix6d Q;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) Q(r, c) = q.at<double>(r, c);
  for (int c = 0; c < 6; ++c) out.explainedVariance[c] = ev.at<double>(0, c);
  out.model = ArMotionModel(weights, Q);
  const YamlNode source = node("source_trajectory");
  if (!source.text()) source.fail("'source_trajectory' must be a string");
  out.sourceTrajectory = *source.text();
  const YamlNode frames = node("frame_count");
  if (frames.integer().value_or(-1) < 0)
    frames.fail("'frame_count' must be a non-negative integer");
  out.frameCount = *frames.integer();
  return out;
}

}  // namespace

void saveMotionModel(const std::filesystem::path& file, const FittedMotionModel& fitted) {
  fitted.model.check();
  const int p = fitted.model.order();
  Eigen::MatrixXd weights(p, 6);
  for (int j = 0; j < p; ++j) weights.row(j) = fitted.model.weights()[j].transpose();
  writeFileAtomically(file, [&](const std::filesystem::path& tmp) {
    cv::FileStorage fs(tmp.string(), cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
    if (!fs.isOpened()) throw Error("cannot write motion model file '" + file.string() + "'");
    fs.writeComment(
        "AR(p) motion model of x = (tx, ty, tz, rx, ry, rz), x_k = vec(T_k T_1^-1): "
        "x_k = sum_j diag(weights[j]) x_{k-j} + e_k, cov(e_k) = Q (reftrack fit-motion)");
    fs << "kind" << (fitted.randomWalk ? "random_walk" : "ar");
    fs << "order" << p;
    fs << "weights" << toMat(weights);
    fs << "Q" << toMat(fitted.model.processNoise());
    fs << "explained_variance" << toMat(fitted.explainedVariance.transpose());
    fs << "source_trajectory" << fitted.sourceTrajectory;
    fs << "frame_count" << fitted.frameCount;
  });
}

FittedMotionModel loadMotionModel(const std::filesystem::path& file) {
  const std::string where = "motion model file '" + file.string() + "'";
  if (!std::filesystem::exists(file)) throw Error(where + " does not exist");
  const YamlNode root = readConfigFile(file, where);
  try {
    return readMotionModel(root);
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
}

}  // namespace reftrack
