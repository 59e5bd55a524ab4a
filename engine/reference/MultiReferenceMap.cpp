// MultiReferenceMap: check, save (format version 3) and load (versions 1, 2 and 3).
#include "engine/reference/MultiReferenceMap.hpp"

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>

#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"
#include "engine/reference/MapFileFields.hpp"

namespace reftrack {

namespace {

constexpr const char* kFormatName = "reftrack-reference-map";

std::string viewName(std::size_t i) { return "views[" + std::to_string(i) + "]"; }
std::string pointName(std::size_t i) { return "points[" + std::to_string(i) + "]"; }

// A file name that stays inside the map folder: no separators, no "." / "..", not map.yml.
bool isPlainFileName(const std::string& name) {
  return !name.empty() && name != "." && name != ".." &&
         name.find_first_of("/\\") == std::string::npos && name != MultiReferenceMap::kFileName;
}

}  // namespace

void MultiReferenceMap::check() const {
  try {
    camera.check();
  } catch (const Error& e) {
    throw Error(std::string("camera: ") + e.what());
  }
  if (denserCorners) {
    try {
      denserCorners->check();
    } catch (const Error& e) {
      throw Error(std::string("denser_corners: ") + e.what());
    }
  }
  if (views.size() < 2)
    throw Error("views: a map needs at least 2 references, got " + std::to_string(views.size()));
  const cv::Size imageSize = camera.imageSize();
  std::set<std::string> names;
  for (std::size_t v = 0; v < views.size(); ++v) {
    const ReferenceView& view = views[v];
    const std::string at = viewName(v);
    if (!isPlainFileName(view.name))
      throw Error(at + ".name '" + view.name + "' is not a plain image file name");
    if (!names.insert(view.name).second)
      throw Error(at + ".name '" + view.name + "' is used by another view");
    if (!view.T.allFinite()) throw Error(at + ".pose is not finite");
    if (view.image.empty()) throw Error(at + ".image is missing");
    if (view.image.size() != imageSize) {
      std::ostringstream ss;
      ss << at << ".image is " << view.image.cols << "x" << view.image.rows << " but the camera is "
         << imageSize.width << "x" << imageSize.height;
      throw Error(ss.str());
    }
    checkCorners(view.corners, at + ".corners", imageSize);
    view.keypoints.check(at + ".keypoints");
  }
  for (std::size_t a = 0; a < views.size(); ++a)
    for (std::size_t b = a + 1; b < views.size(); ++b)
      if (RigidPose::translationDistance(views[a].T.inverse(), views[b].T.inverse()) < 1e-6 &&
          RigidPose::rotationDistance(views[a].T, views[b].T) < 1e-9)
        throw Error(viewName(b) + ".pose is the same as " + viewName(a) + ".pose");
  for (std::size_t p = 0; p < points.size(); ++p) {
    const MapPoint& point = points[p];
    const std::string at = pointName(p);
    if (!point.world.allFinite()) throw Error(at + ".world is not finite");
    if (point.observations.size() < 2)
      throw Error(at + ".observations: " + std::to_string(point.observations.size()) +
                  " observation(s), a point needs at least 2");
    std::set<int> seen;
    for (std::size_t o = 0; o < point.observations.size(); ++o) {
      const PointObservation& obs = point.observations[o];
      const std::string oi = at + ".observations[" + std::to_string(o) + "]";
      if (obs.view < 0 || obs.view >= size())
        throw Error(oi + ".view " + std::to_string(obs.view) + " is out of range (" +
                    std::to_string(size()) + " views)");
      const auto& corners = views[static_cast<std::size_t>(obs.view)].corners;
      if (obs.corner < 0 || obs.corner >= static_cast<int>(corners.size()))
        throw Error(oi + ".corner " + std::to_string(obs.corner) + " is out of range (" +
                    viewName(static_cast<std::size_t>(obs.view)) + " has " +
                    std::to_string(corners.size()) + " corners)");
      if (!seen.insert(obs.view).second)
        throw Error(oi + ".view " + std::to_string(obs.view) + " appears twice in one point");
      if (obs.peak) {
        if (!std::isfinite(obs.peak->x) || !std::isfinite(obs.peak->y))
          throw Error(oi + ".peak is not finite");
        if (!liesInsideImage(*obs.peak, imageSize))
          throw Error(oi + ".peak lies outside the image");
      }
      const Eigen::Vector3d inCamera = views[static_cast<std::size_t>(obs.view)].T * point.world;
      if (!(inCamera.z() > 0.0))
        throw Error(at + ".world lies behind the camera of " +
                    viewName(static_cast<std::size_t>(obs.view)));
    }
  }
}

void MultiReferenceMap::save(const std::filesystem::path& folder) const {
  check();
  std::filesystem::create_directories(folder);
  for (const ReferenceView& view : views) {
    const std::filesystem::path target = folder / view.name;
    writeFileAtomically(target, [&](const std::filesystem::path& tmp) {
      if (!cv::imwrite(tmp.string(), view.image)) throw Error("cannot write " + target.string());
    });
  }
  writeFileAtomically(folder / kFileName, [&](const std::filesystem::path& tmp) {
    cv::FileStorage fs(tmp.string(), cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
    fs << "format" << kFormatName;
    fs << "version" << kFormatVersion;
    writeMapCamera(fs, camera);
    fs << "pose_source" << poseSource;
    fs << "keypoint_kind" << keypointKind;
    fs << "views"
       << "[";
    for (std::size_t v = 0; v < views.size(); ++v) {
      const ReferenceView& view = views[v];
      fs << "{";
      fs << "name" << view.name;
      fs << "T" << poseToMat(view.T);
      fs << "anchored" << static_cast<int>(view.anchored);
      fs << "corners" << cornersToMat(view.corners);
      view.keypoints.write(fs, "keypoints");
      fs << "}";
    }
    fs << "]";
    // points: world xyz per row; observations: (point, view, corner) per row, grouped by point;
    // observation_peaks: the measured pixel (x, y) of each observation row (measuredPixel).
    cv::Mat world(static_cast<int>(points.size()), 3, CV_64F);
    std::size_t observationCount = 0;
    for (const MapPoint& p : points) observationCount += p.observations.size();
    cv::Mat obs(static_cast<int>(observationCount), 3, CV_32S);
    cv::Mat peaks(static_cast<int>(observationCount), 2, CV_32F);
    int row = 0;
    for (std::size_t p = 0; p < points.size(); ++p) {
      for (int k = 0; k < 3; ++k) world.at<double>(static_cast<int>(p), k) = points[p].world[k];
      for (const PointObservation& o : points[p].observations) {
        obs.at<int>(row, 0) = static_cast<int>(p);
        obs.at<int>(row, 1) = o.view;
        obs.at<int>(row, 2) = o.corner;
        const cv::Point2f peak = measuredPixel(o);
        peaks.at<float>(row, 0) = peak.x;
        peaks.at<float>(row, 1) = peak.y;
        ++row;
      }
    }
    fs << "point_count" << static_cast<int>(points.size());
    fs << "points" << world << "observations" << obs << "observation_peaks" << peaks;
    fs << "preparation_params" << preparationParams;
    if (denserCorners) {
      fs << "denser_corners"
         << "{";
      denserCorners->write(fs);
      fs << "}";
    }
    fs.release();
  });
}

MultiReferenceMap MultiReferenceMap::load(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / kFileName;
  const std::string where = "reference map '" + file.string() + "'";
  const YamlNode root = openReferenceMapFile(file);
  const MapFieldReader read(where, folder);
  if (read.readText(root, "format", "format") != kFormatName)
    throw Error(where + " is not a reftrack reference map");
  const int version = read.readInt(root, "version", "version");
  if (version == ReferenceMap::kFormatVersion) return fromPair(ReferenceMap::load(folder));
  // Version 2 is version 3 without observation_peaks.
  constexpr int kVersionWithoutPeaks = 2;
  if (version != kFormatVersion && version != kVersionWithoutPeaks)
    throw Error(where + " has format version " + std::to_string(version) +
                "; this reftrack reads versions " + std::to_string(ReferenceMap::kFormatVersion) +
                ", " + std::to_string(kVersionWithoutPeaks) + " and " +
                std::to_string(kFormatVersion) +
                (version > kFormatVersion ? " (written by a newer reftrack?)" : ""));
  const bool hasPeaks = version >= kFormatVersion;

  return readCheckedMap<MultiReferenceMap>(where, [&](MultiReferenceMap& map) {
    std::vector<std::string> rootKeys = {"format",
                                         "version",
                                         "image_width",
                                         "image_height",
                                         "camera_matrix",
                                         "distortion_coefficients",
                                         "pose_source",
                                         "keypoint_kind",
                                         "views",
                                         "point_count",
                                         "points",
                                         "observations",
                                         "preparation_params"};
    if (hasPeaks) {
      rootKeys.push_back("observation_peaks");
      rootKeys.push_back("denser_corners");
    }
    read.requireKnown(root, rootKeys);
    map.camera = read.readCamera(root);
    map.poseSource = root["pose_source"].text().value_or("");
    map.keypointKind = root["keypoint_kind"].text().value_or("");
    map.preparationParams = root["preparation_params"].text().value_or("");
    if (const YamlNode denser = root["denser_corners"]; denser.present()) {
      if (!denser.isMap()) throw Error(where + ": field 'denser_corners' is not a map");
      CornerParams corners;
      try {
        corners.read(denser);
      } catch (const Error& e) {
        throw Error(where + ": field 'denser_corners': " + e.what());
      }
      map.denserCorners = corners;
    }

    const YamlNode viewsNode = read.need(root, "views", "views");
    if (!viewsNode.isList()) throw Error(where + ": field 'views' is not a list");
    for (std::size_t v = 0; v < viewsNode.size(); ++v) {
      const YamlNode node = viewsNode.item(v);
      const std::string at = viewName(v);
      if (!node.isMap()) throw Error(where + ": field '" + at + "' is not a map");
      read.requireKnown(node, {"name", "T", "anchored", "corners", "keypoints"});
      ReferenceView view;
      view.name = read.readText(node, "name", at + ".name");
      view.T = read.readPose(node, "T", at + ".T");
      view.anchored = read.readInt(node, "anchored", at + ".anchored") != 0;
      view.corners = read.readCorners(node, "corners", at + ".corners");
      try {
        view.keypoints = ReferenceKeypoints::read(node["keypoints"]);
      } catch (const Error& e) {
        throw Error(where + ": " + e.what());
      }
      if (!isPlainFileName(view.name))
        throw Error(where + ": field '" + at + ".name' ('" + view.name +
                    "') is not a plain image file name");
      view.image = read.readImage(view.name, at + ".name");
      map.views.push_back(std::move(view));
    }

    const int pointCount = read.readInt(root, "point_count", "point_count");
    if (pointCount < 0) throw Error(where + ": field 'point_count' is negative");
    cv::Mat world = read.readMat(root, "points", "points", pointCount, 3);
    cv::Mat obs = read.readMat(root, "observations", "observations", -1, 3);
    if (!world.empty()) world.convertTo(world, CV_64F);
    if (!obs.empty()) obs.convertTo(obs, CV_32S);
    cv::Mat peaks;
    if (hasPeaks) {
      peaks = read.readMat(root, "observation_peaks", "observation_peaks", obs.rows, 2);
      if (!peaks.empty()) peaks.convertTo(peaks, CV_32F);
    }
    map.points.resize(static_cast<std::size_t>(pointCount));
    for (int p = 0; p < pointCount; ++p)
      map.points[static_cast<std::size_t>(p)].world =
          Eigen::Vector3d(world.at<double>(p, 0), world.at<double>(p, 1), world.at<double>(p, 2));
    for (int r = 0; r < obs.rows; ++r) {
      const int p = obs.at<int>(r, 0);
      if (p < 0 || p >= pointCount)
        throw Error(where + ": field 'observations' row " + std::to_string(r) + " names point " +
                    std::to_string(p) + " of " + std::to_string(pointCount));
      PointObservation o{obs.at<int>(r, 1), obs.at<int>(r, 2)};
      if (hasPeaks) o.peak = cv::Point2f(peaks.at<float>(r, 0), peaks.at<float>(r, 1));
      map.points[static_cast<std::size_t>(p)].observations.push_back(o);
    }
  });
}

}  // namespace reftrack
