#include "app/viewer/ViewerSettings.hpp"

#include "engine/config/ConfigValue.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

void ViewerSettings::check() const {
  tracker.check();
  overlay.check();
}

ViewerSettings ViewerSettings::load(const std::filesystem::path& file) {
  ViewerSettings s;
  s.tracker = TrackerParams::load(file);  // names the file and key on error
  readParameterFile(file, [&](const cv::FileNode& root) { s.overlay.read(root["overlay"]); });
  return s;
}

void ViewerSettings::save(const std::filesystem::path& file) const {
  check();
  writeFileAtomically(file, [&](const std::filesystem::path& tmp) {
    cv::FileStorage fs(tmp.string(), cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
    if (!fs.isOpened()) throw Error("cannot write parameter file '" + file.string() + "'");
    tracker.write(fs);
    fs << "overlay"
       << "{";
    overlay.write(fs);
    fs << "}";
    fs.release();
  });
}

}  // namespace reftrack::app
