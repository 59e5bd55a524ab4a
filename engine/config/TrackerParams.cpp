#include "engine/config/TrackerParams.hpp"

#include "engine/config/ConfigValue.hpp"
#include "engine/config/FieldDescriber.hpp"
#include "engine/config/ParamFields.hpp"
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

template <class Self, class Field>
void TrackerParams::fields(Self& p, const Field& field) {
  field("mode", p.mode, TextForm<TrackingMode>{toString, parseTrackingMode})
      .help(
          "6dof: the camera pose against a prepared reference map; homography: a plane registered "
          "to a reference frame");
  field(p.corners);
  field(p.correlation);
  field(p.ransac);
  field(p.homography);
  field(p.wideBaseline);
  field(p.pose);
  field(p.relocalisation);
  field(p.references);
}

template struct ParamSection<TrackerParams>;
template void TrackerParams::fields(const TrackerParams&, const FieldDescriber&);

void TrackerParams::read(const YamlNode& root) {
  if (root.isNull()) return;  // an empty file: the defaults
  if (!root.isMap()) root.fail("parameters must be a map of sections");
  readFields(*this, root, kOtherSections);
}

TrackerParams TrackerParams::load(const std::filesystem::path& file) {
  TrackerParams p;
  readParameterFile(file, [&](const YamlNode& root) { p.read(root); });
  return p;
}

TrackerParams TrackerParams::parse(const std::string& text, const std::string& what) {
  TrackerParams p;
  readParameterText(text, what, [&](const YamlNode& root) { p.read(root); });
  return p;
}

void TrackerParams::save(const std::filesystem::path& file) const {
  check();
  writeParameterFile(file, [&](cv::FileStorage& fs) { write(fs); });
}

}  // namespace reftrack
