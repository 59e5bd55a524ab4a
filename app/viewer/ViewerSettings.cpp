#include "app/viewer/ViewerSettings.hpp"

#include "engine/config/ParamFields.hpp"

namespace reftrack::app {

void ViewerSettings::check() const {
  tracker.check();
  overlay.check();
}

ViewerSettings ViewerSettings::load(const std::filesystem::path& file) {
  ViewerSettings s;
  s.tracker = TrackerParams::load(file);  // names the file and key on error
  readParameterFile(file, [&](const YamlNode& root) { s.overlay.read(root["overlay"]); });
  return s;
}

void ViewerSettings::save(const std::filesystem::path& file) const {
  check();
  writeParameterFile(file, [&](cv::FileStorage& fs) {
    tracker.write(fs);
    FieldWriter{fs}(overlay);  // its own section
  });
}

}  // namespace reftrack::app
