#include "engine/config/TrackerParams.hpp"

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

std::string toString(TrackingMode mode) {
  return mode == TrackingMode::SixDof ? "6dof" : "homography";
}

TrackingMode parseTrackingMode(const std::string& text) {
  if (text == "6dof") return TrackingMode::SixDof;
  if (text == "homography") return TrackingMode::Homography;
  throw Error("parameter 'mode' must be '6dof' or 'homography', got '" + text + "'");
}

void TrackerParams::check() const {
  corners.check();
  correlation.check();
  ransac.check();
  homography.check();
  wideBaseline.check();
  pose.check();
  relocalisation.check();
  references.check();
}

void TrackerParams::write(cv::FileStorage& fs) const {
  fs << "mode" << toString(mode);
  fs << "corners"
     << "{";
  corners.write(fs);
  fs << "}"
     << "correlation"
     << "{";
  correlation.write(fs);
  fs << "}"
     << "ransac"
     << "{";
  ransac.write(fs);
  fs << "}"
     << "homography"
     << "{";
  homography.write(fs);
  fs << "}"
     << "wide_baseline"
     << "{";
  wideBaseline.write(fs);
  fs << "}"
     << "pose"
     << "{";
  pose.write(fs);
  fs << "}"
     << "relocalisation"
     << "{";
  relocalisation.write(fs);
  fs << "}"
     << "references"
     << "{";
  references.write(fs);
  fs << "}";
}

void TrackerParams::read(const cv::FileNode& root) {
  if (!root.isMap()) throw Error("parameters must be a map of sections");
  requireKeysWrittenBy(
      root, "", [](cv::FileStorage& fs) { TrackerParams{}.write(fs); }, kOtherSections);
  std::string modeName = toString(mode);
  readConfigValue(root, "", "mode", modeName);
  mode = parseTrackingMode(modeName);
  corners.read(root["corners"]);
  correlation.read(root["correlation"]);
  ransac.read(root["ransac"]);
  homography.read(root["homography"]);
  wideBaseline.read(root["wide_baseline"]);
  pose.read(root["pose"]);
  relocalisation.read(root["relocalisation"]);
  references.read(root["references"]);
}

TrackerParams TrackerParams::load(const std::filesystem::path& file) {
  TrackerParams p;
  readParameterFile(file, [&](const cv::FileNode& root) { p.read(root); });
  return p;
}

void TrackerParams::save(const std::filesystem::path& file) const {
  check();
  writeFileAtomically(file, [&](const std::filesystem::path& tmp) {
    cv::FileStorage fs(tmp.string(), cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
    if (!fs.isOpened()) throw Error("cannot write parameter file '" + file.string() + "'");
    write(fs);
    fs.release();
  });
}

}  // namespace reftrack
