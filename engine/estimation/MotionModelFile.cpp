#include "engine/estimation/MotionModelFile.hpp"

#include <cmath>
#include <opencv2/core.hpp>

#include "engine/config/ConfigFile.hpp"
#include "engine/config/KnownKeys.hpp"
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
  cv::FileStorage fs = openConfigFile(file, where, "is not valid OpenCV YAML");
  try {
    requireKnownKeys(fs.root(), "",
                     {"kind", "order", "weights", "Q", "explained_variance", "source_trajectory",
                      "frame_count"});
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  auto node = [&](const char* key) {
    cv::FileNode n = fs[key];
    if (n.empty()) throw Error(where + ": missing key '" + key + "'");
    return n;
  };
  auto matrix = [&](const char* key, int rows, int cols) {
    cv::Mat m;
    try {
      node(key) >> m;
    } catch (const cv::Exception& e) {
      throw Error(where + ": '" + key + "' is not a matrix: " + e.err);
    }
    if (m.rows != rows || m.cols != cols)
      throw Error(where + ": '" + key + "' must be " + std::to_string(rows) + "x" +
                  std::to_string(cols) + ", got " + std::to_string(m.rows) + "x" +
                  std::to_string(m.cols));
    m.convertTo(m, CV_64F);
    if (!cv::checkRange(m)) throw Error(where + ": '" + key + "' contains NaN or infinity");
    return m;
  };

  FittedMotionModel out;
  const cv::FileNode kind = node("kind");
  if (!kind.isString() ||
      (static_cast<std::string>(kind) != "ar" && static_cast<std::string>(kind) != "random_walk"))
    throw Error(where + ": 'kind' must be \"ar\" or \"random_walk\"");
  out.randomWalk = static_cast<std::string>(kind) == "random_walk";
  const cv::FileNode orderNode = node("order");
  if (!orderNode.isInt() || static_cast<int>(orderNode) < 1 || static_cast<int>(orderNode) > 100)
    throw Error(where + ": 'order' must be an integer from 1 to 100");
  const int p = static_cast<int>(orderNode);
  const cv::Mat w = matrix("weights", p, 6), q = matrix("Q", 6, 6),
                ev = matrix("explained_variance", 1, 6);
  std::vector<Vector6d> weights(p);
  for (int j = 0; j < p; ++j)
    for (int c = 0; c < 6; ++c) weights[j][c] = w.at<double>(j, c);
  Matrix6d Q;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) Q(r, c) = q.at<double>(r, c);
  for (int c = 0; c < 6; ++c) out.explainedVariance[c] = ev.at<double>(0, c);
  try {
    out.model = ArMotionModel(weights, Q);
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  const cv::FileNode source = node("source_trajectory");
  if (!source.isString()) throw Error(where + ": 'source_trajectory' must be a string");
  out.sourceTrajectory = static_cast<std::string>(source);
  const cv::FileNode frames = node("frame_count");
  if (!frames.isInt() || static_cast<int>(frames) < 0)
    throw Error(where + ": 'frame_count' must be a non-negative integer");
  out.frameCount = static_cast<int>(frames);
  return out;
}

}  // namespace reftrack
