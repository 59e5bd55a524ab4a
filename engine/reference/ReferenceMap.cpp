#include "engine/reference/ReferenceMap.hpp"

#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "engine/config/ConfigFile.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"
#include "engine/reference/MapFileFields.hpp"

namespace reftrack {

namespace {

constexpr const char* kImageA = "reference_a.png";
constexpr const char* kImageB = "reference_b.png";

}  // namespace

YamlNode openReferenceMapFile(const std::filesystem::path& file) {
  const std::string where = "reference map '" + file.string() + "'";
  if (!std::filesystem::exists(file))
    throw Error(where + " does not exist (run `reftrack prepare` first)");
  return readConfigFile(file, where, "is corrupt or truncated");
}

void ReferenceMap::check() const {
  camera.check();
  if (denserCorners) {
    try {
      denserCorners->check();
    } catch (const Error& e) {
      throw Error(std::string("denser corners: ") + e.what());
    }
  }
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
    writeMapCamera(fs, camera);
    fs << "T_A" << poseToMat(T_A) << "T_B" << poseToMat(T_B);
    fs << "reference_a" << kImageA << "reference_b" << kImageB;
    fs << "pose_source" << poseSource;
    fs << "corners_a" << cornersToMat(cornersA) << "corners_b" << cornersToMat(cornersB);
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
  const YamlNode root = openReferenceMapFile(file);
  const MapFieldReader read(where, folder);
  return readCheckedMap<ReferenceMap>(where, [&](ReferenceMap& map) {
    read.requireKnown(
        root, {"format", "version", "image_width", "image_height", "camera_matrix",
               "distortion_coefficients", "T_A", "T_B", "reference_a", "reference_b", "pose_source",
               "corners_a", "corners_b", "matches", "points_a", "preparation_params"});
    if (read.readText(root, "format", "format") != "reftrack-reference-map")
      throw Error(where + " is not a reftrack reference map");
    const int version = read.readInt(root, "version", "version");
    if (version != kFormatVersion)
      throw Error(where + " has format version " + std::to_string(version) +
                  "; this reftrack reads version " + std::to_string(kFormatVersion));
    map.camera = read.readCamera(root);
    map.T_A = read.readPose(root, "T_A", "T_A");
    map.T_B = read.readPose(root, "T_B", "T_B");
    map.poseSource = root["pose_source"].text().value_or("");
    map.preparationParams = root["preparation_params"].text().value_or("");
    map.cornersA = read.readCorners(root, "corners_a", "corners_a");
    map.cornersB = read.readCorners(root, "corners_b", "corners_b");
    cv::Mat idx = read.readMat(root, "matches", "matches", -1, 2),
            pts = read.readMat(root, "points_a", "points_a", -1, 3);
    if (idx.rows != pts.rows)
      throw Error(where + ": 'matches' and 'points_a' differ in length (truncated file?)");
    if (!pts.empty()) pts.convertTo(pts, CV_64F);
    if (!idx.empty()) idx.convertTo(idx, CV_32S);
    for (int i = 0; i < idx.rows; ++i)
      map.matches.push_back(
          {idx.at<int>(i, 0), idx.at<int>(i, 1),
           Eigen::Vector3d(pts.at<double>(i, 0), pts.at<double>(i, 1), pts.at<double>(i, 2))});
    const auto readImage = [&](const char* key) {
      return read.readImage(read.readText(root, key, key), key);
    };
    map.imageA = readImage("reference_a");
    map.imageB = readImage("reference_b");
  });
}

}  // namespace reftrack
