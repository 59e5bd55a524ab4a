#include "engine/reference/ReferenceMap.hpp"

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "engine/config/ConfigFile.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

constexpr const char* kImageA = "reference_a.png";
constexpr const char* kImageB = "reference_b.png";

cv::Mat poseToMat(const RigidPose& T) {
  cv::Mat m(4, 4, CV_64F);
  const Eigen::Matrix4d M = T.matrix4();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m.at<double>(r, c) = M(r, c);
  return m;
}

void checkCorners(const std::vector<ReferenceCorner>& corners, const char* name, cv::Size size) {
  for (size_t i = 0; i < corners.size(); ++i) {
    const auto& c = corners[i];
    if (!std::isfinite(c.pixel.x) || !std::isfinite(c.pixel.y) || !std::isfinite(c.rmsContrast))
      throw Error(std::string(name) + "[" + std::to_string(i) + "] is not finite");
    if (c.pixel.x < -0.5f || c.pixel.y < -0.5f || c.pixel.x > size.width - 0.5f ||
        c.pixel.y > size.height - 0.5f)
      throw Error(std::string(name) + "[" + std::to_string(i) + "] lies outside the image");
  }
}

}  // namespace

cv::FileStorage openReferenceMapFile(const std::filesystem::path& file) {
  const std::string where = "reference map '" + file.string() + "'";
  if (!std::filesystem::exists(file))
    throw Error(where + " does not exist (run `reftrack prepare` first)");
  return openConfigFile(file, where, "is corrupt or truncated");
}

void ReferenceMap::check() const {
  camera.check();
  if (!T_A.allFinite() || !T_B.allFinite()) throw Error("reference poses T_A/T_B are not finite");
  if (imageA.empty() || imageB.empty()) throw Error("reference images are missing");
  if (imageA.size() != camera.imageSize() || imageB.size() != camera.imageSize()) {
    std::ostringstream ss;
    ss << "reference images are " << imageA.cols << "x" << imageA.rows << " and " << imageB.cols
       << "x" << imageB.rows << " but the camera is " << camera.imageSize().width << "x"
       << camera.imageSize().height;
    throw Error(ss.str());
  }
  if (RigidPose::translationDistance(T_A.inverse(), T_B.inverse()) < 1e-6)
    throw Error("the two reference cameras are at the same place: no baseline to triangulate from");
  checkCorners(cornersA, "cornersA", camera.imageSize());
  checkCorners(cornersB, "cornersB", camera.imageSize());
  for (size_t i = 0; i < matches.size(); ++i) {
    const auto& m = matches[i];
    if (m.cornerA < 0 || m.cornerA >= static_cast<int>(cornersA.size()) || m.cornerB < 0 ||
        m.cornerB >= static_cast<int>(cornersB.size()))
      throw Error("matches[" + std::to_string(i) + "] refers to a corner that does not exist");
    if (!m.pointA.allFinite() || m.pointA.z() <= 0.0)
      throw Error("matches[" + std::to_string(i) +
                  "] has a 3D point that is not finite or lies behind camera A");
  }
}

void ReferenceMap::save(const std::filesystem::path& folder) const {
  check();
  std::filesystem::create_directories(folder);
  const auto writeImage = [&](const char* name, const cv::Mat& img) {
    writeFileAtomically(folder / name, [&](const std::filesystem::path& tmp) {
      if (!cv::imwrite(tmp.string(), img)) throw Error("cannot write " + (folder / name).string());
    });
  };
  writeImage(kImageA, imageA);
  writeImage(kImageB, imageB);
  writeFileAtomically(folder / kFileName, [&](const std::filesystem::path& tmp) {
    cv::FileStorage fs(tmp.string(), cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
    fs << "format"
       << "reftrack-reference-map";
    fs << "version" << kFormatVersion;
    fs << "image_width" << camera.imageSize().width << "image_height" << camera.imageSize().height;
    fs << "camera_matrix" << cv::Mat(camera.Kcv());
    fs << "distortion_coefficients" << cv::Mat(camera.distortion(), true);
    fs << "T_A" << poseToMat(T_A) << "T_B" << poseToMat(T_B);
    fs << "reference_a" << kImageA << "reference_b" << kImageB;
    fs << "pose_source" << poseSource;
    const auto cornerMat = [](const std::vector<ReferenceCorner>& cs) {
      cv::Mat m(static_cast<int>(cs.size()), 3, CV_32F);
      for (size_t i = 0; i < cs.size(); ++i) {
        m.at<float>(static_cast<int>(i), 0) = cs[i].pixel.x;
        m.at<float>(static_cast<int>(i), 1) = cs[i].pixel.y;
        m.at<float>(static_cast<int>(i), 2) = cs[i].rmsContrast;
      }
      return m;
    };
    fs << "corners_a" << cornerMat(cornersA) << "corners_b" << cornerMat(cornersB);
    cv::Mat idx(static_cast<int>(matches.size()), 2, CV_32S),
        pts(static_cast<int>(matches.size()), 3, CV_64F);
    for (size_t i = 0; i < matches.size(); ++i) {
      const int r = static_cast<int>(i);
      idx.at<int>(r, 0) = matches[i].cornerA;
      idx.at<int>(r, 1) = matches[i].cornerB;
      for (int k = 0; k < 3; ++k) pts.at<double>(r, k) = matches[i].pointA[k];
    }
    fs << "matches" << idx << "points_a" << pts;
    fs << "preparation_params" << preparationParams;
    fs.release();
  });
}

ReferenceMap ReferenceMap::load(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / kFileName;
  const std::string where = "reference map '" + file.string() + "'";
  cv::FileStorage fs = openReferenceMapFile(file);
  ReferenceMap map;
  try {
    try {
      requireKnownKeys(
          fs.root(), "",
          {"format", "version", "image_width", "image_height", "camera_matrix",
           "distortion_coefficients", "T_A", "T_B", "reference_a", "reference_b", "pose_source",
           "corners_a", "corners_b", "matches", "points_a", "preparation_params"});
    } catch (const Error& e) {
      throw Error(where + ": " + e.what());
    }
    const auto need = [&](const char* key) {
      cv::FileNode n = fs[key];
      if (n.empty()) throw Error(where + ": missing field '" + key + "' (truncated file?)");
      return n;
    };
    if (static_cast<std::string>(need("format")) != "reftrack-reference-map")
      throw Error(where + " is not a reftrack reference map");
    const int version = static_cast<int>(need("version"));
    if (version != kFormatVersion)
      throw Error(where + " has format version " + std::to_string(version) +
                  "; this reftrack reads version " + std::to_string(kFormatVersion));
    const auto readMat = [&](const char* key, int rows, int cols) {
      cv::Mat m;
      need(key) >> m;
      if ((rows >= 0 && m.rows != rows) || (cols >= 0 && !m.empty() && m.cols != cols))
        throw Error(where + ": field '" + key + "' has the wrong shape");
      return m;
    };
    cv::Mat K = readMat("camera_matrix", 3, 3), D;
    K.convertTo(K, CV_64F);
    fs["distortion_coefficients"] >> D;
    Eigen::Matrix3d Ke;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) Ke(r, c) = K.at<double>(r, c);
    std::vector<double> dist;
    if (!D.empty()) {
      D.convertTo(D, CV_64F);
      D = D.reshape(1, 1);
      dist.assign(D.ptr<double>(), D.ptr<double>() + D.cols);
    }
    map.camera = PinholeCamera(
        Ke, cv::Size(static_cast<int>(need("image_width")), static_cast<int>(need("image_height"))),
        dist);
    const auto readPose = [&](const char* key) {
      cv::Mat m = readMat(key, 4, 4);
      m.convertTo(m, CV_64F);
      Eigen::Matrix4d M;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) M(r, c) = m.at<double>(r, c);
      if (!M.allFinite()) throw Error(where + ": field '" + key + "' is not finite");
      return RigidPose::fromMatrix4(M);
    };
    map.T_A = readPose("T_A");
    map.T_B = readPose("T_B");
    map.poseSource = static_cast<std::string>(fs["pose_source"]);
    map.preparationParams = static_cast<std::string>(fs["preparation_params"]);
    const auto readCorners = [&](const char* key) {
      cv::Mat m = readMat(key, -1, 3);
      std::vector<ReferenceCorner> cs(m.rows);
      if (!m.empty()) m.convertTo(m, CV_32F);
      for (int i = 0; i < m.rows; ++i)
        cs[i] = {{m.at<float>(i, 0), m.at<float>(i, 1)}, m.at<float>(i, 2)};
      return cs;
    };
    map.cornersA = readCorners("corners_a");
    map.cornersB = readCorners("corners_b");
    cv::Mat idx = readMat("matches", -1, 2), pts = readMat("points_a", -1, 3);
    if (idx.rows != pts.rows)
      throw Error(where + ": 'matches' and 'points_a' differ in length (truncated file?)");
    if (!pts.empty()) pts.convertTo(pts, CV_64F);
    if (!idx.empty()) idx.convertTo(idx, CV_32S);
    for (int i = 0; i < idx.rows; ++i)
      map.matches.push_back(
          {idx.at<int>(i, 0), idx.at<int>(i, 1),
           Eigen::Vector3d(pts.at<double>(i, 0), pts.at<double>(i, 1), pts.at<double>(i, 2))});
    const auto readImage = [&](const char* key) {
      const std::filesystem::path p = folder / static_cast<std::string>(need(key));
      if (!std::filesystem::exists(p))
        throw Error(where + ": reference image '" + p.string() + "' is missing");
      cv::Mat img = cv::imread(p.string(), cv::IMREAD_UNCHANGED);
      if (img.empty()) throw Error(where + ": reference image '" + p.string() + "' cannot be read");
      return img;
    };
    map.imageA = readImage("reference_a");
    map.imageB = readImage("reference_b");
  } catch (const cv::Exception& e) {
    throw Error(where + " has a malformed field: " + e.err);
  }
  try {
    map.check();
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  return map;
}

}  // namespace reftrack
