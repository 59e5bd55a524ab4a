#include "engine/reference/MapFileFields.hpp"

#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "engine/config/KnownKeys.hpp"
#include "engine/config/YamlMatrix.hpp"

namespace reftrack {

void writeMapCamera(cv::FileStorage& fs, const PinholeCamera& camera) {
  fs << "image_width" << camera.imageSize().width << "image_height" << camera.imageSize().height;
  fs << "camera_matrix" << cv::Mat(camera.Kcv());
  fs << "distortion_coefficients" << cv::Mat(camera.distortion(), true);
}

cv::Mat poseToMat(const RigidPose& T) {
  cv::Mat m(4, 4, CV_64F);
  const Eigen::Matrix4d M = T.matrix4();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m.at<double>(r, c) = M(r, c);
  return m;
}

cv::Mat cornersToMat(const std::vector<ReferenceCorner>& corners) {
  cv::Mat m(static_cast<int>(corners.size()), 3, CV_32F);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const int r = static_cast<int>(i);
    m.at<float>(r, 0) = corners[i].pixel.x;
    m.at<float>(r, 1) = corners[i].pixel.y;
    m.at<float>(r, 2) = corners[i].rmsContrast;
  }
  return m;
}

bool liesInsideImage(cv::Point2f p, cv::Size size) {
  return p.x >= -0.5f && p.y >= -0.5f && p.x <= size.width - 0.5f && p.y <= size.height - 0.5f;
}

void checkCorners(const std::vector<ReferenceCorner>& corners, const std::string& name,
                  cv::Size imageSize) {
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const ReferenceCorner& c = corners[i];
    const std::string at = name + "[" + std::to_string(i) + "]";
    if (!std::isfinite(c.pixel.x) || !std::isfinite(c.pixel.y) || !std::isfinite(c.rmsContrast))
      throw Error(at + " is not finite");
    if (!liesInsideImage(c.pixel, imageSize)) throw Error(at + " lies outside the image");
  }
}

void MapFieldReader::requireKnown(const YamlNode& node,
                                  const std::vector<std::string>& known) const {
  try {
    requireKnownKeys(node, known);
  } catch (const Error& e) {
    throw Error(where_ + ": " + e.what());
  }
}

YamlNode MapFieldReader::need(const YamlNode& parent, const std::string& key,
                              const std::string& name) const {
  const YamlNode n = parent[key];
  if (!n.present()) throw Error(where_ + ": missing field '" + name + "' (truncated file?)");
  return n;
}

cv::Mat MapFieldReader::readMat(const YamlNode& parent, const std::string& key,
                                const std::string& name, int rows, int cols) const {
  const YamlNode n = need(parent, key, name);
  cv::Mat m;
  try {
    m = readYamlMatrix(n);
  } catch (const Error& e) {
    throw Error(where_ + ": " + e.what());
  }
  if ((rows >= 0 && m.rows != rows) || (cols >= 0 && !m.empty() && m.cols != cols) ||
      m.channels() != 1)
    throw Error(where_ + ": field '" + name + "' has the wrong shape (" + std::to_string(m.rows) +
                "x" + std::to_string(m.cols) + ")");
  return m;
}

int MapFieldReader::readInt(const YamlNode& parent, const std::string& key,
                            const std::string& name) const {
  const YamlNode n = need(parent, key, name);
  if (!n.integer())
    throw Error(where_ + ": line " + std::to_string(n.line()) + ": field '" + name +
                "' must be an integer");
  return *n.integer();
}

std::string MapFieldReader::readText(const YamlNode& parent, const std::string& key,
                                     const std::string& name) const {
  const YamlNode n = need(parent, key, name);
  if (!n.text())
    throw Error(where_ + ": line " + std::to_string(n.line()) + ": field '" + name +
                "' must be text");
  return *n.text();
}

PinholeCamera MapFieldReader::readCamera(const YamlNode& root) const {
  cv::Mat K = readMat(root, "camera_matrix", "camera_matrix", 3, 3), D;
  K.convertTo(K, CV_64F);
  if (root["distortion_coefficients"].present())
    D = readMat(root, "distortion_coefficients", "distortion_coefficients", -1, -1);
  Eigen::Matrix3d Ke;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Ke(r, c) = K.at<double>(r, c);
  std::vector<double> distortion;
  if (!D.empty()) {
    D.convertTo(D, CV_64F);
    D = D.reshape(1, 1);
    distortion.assign(D.ptr<double>(), D.ptr<double>() + D.cols);
  }
  return PinholeCamera(Ke,
                       cv::Size(readInt(root, "image_width", "image_width"),
                                readInt(root, "image_height", "image_height")),
                       distortion);
}

RigidPose MapFieldReader::readPose(const YamlNode& parent, const std::string& key,
                                   const std::string& name) const {
  cv::Mat T = readMat(parent, key, name, 4, 4);
  T.convertTo(T, CV_64F);
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) M(r, c) = T.at<double>(r, c);
  if (!M.allFinite()) throw Error(where_ + ": field '" + name + "' is not finite");
  if ((M.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-9 ||
      (M.topLeftCorner<3, 3>() * M.topLeftCorner<3, 3>().transpose() - Eigen::Matrix3d::Identity())
              .norm() > 1e-6)
    throw Error(where_ + ": field '" + name + "' is not a rigid transform");
  return RigidPose::fromMatrix4(M);
}

std::vector<ReferenceCorner> MapFieldReader::readCorners(const YamlNode& parent,
                                                         const std::string& key,
                                                         const std::string& name) const {
  cv::Mat m = readMat(parent, key, name, -1, 3);
  if (!m.empty()) m.convertTo(m, CV_32F);
  std::vector<ReferenceCorner> corners(static_cast<std::size_t>(m.rows));
  for (int i = 0; i < m.rows; ++i)
    corners[static_cast<std::size_t>(i)] = {{m.at<float>(i, 0), m.at<float>(i, 1)},
                                            m.at<float>(i, 2)};
  return corners;
}

cv::Mat MapFieldReader::readImage(const std::string& fileName, const std::string& name) const {
  const std::filesystem::path path = folder_ / fileName;
  // The name comes from the file: one the file system refuses (too long, ...) is missing too.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(where_ + ": reference image '" + path.string() + "' (" + name + ") is missing" +
                (ec && ec != std::errc::no_such_file_or_directory ? " (" + ec.message() + ")"
                                                                  : std::string()));
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  if (image.empty())
    throw Error(where_ + ": reference image '" + path.string() + "' cannot be read");
  return image;
}

}  // namespace reftrack
