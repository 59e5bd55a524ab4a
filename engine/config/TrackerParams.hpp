#pragma once
// TrackerParams: every tracking parameter in one YAML file (the file `--params` accepts and the
// viewer's panels edit). Sections: corners, correlation, ransac, homography, wide_baseline, pose,
// relocalisation, references (N-reference maps), plus `mode: 6dof|homography`. Missing keys keep
// the paper's defaults; an unknown key or section is an error naming the nearest known one.
#include <filesystem>
#include <string>
#include <vector>

#include "engine/config/CornerParams.hpp"
#include "engine/config/CorrelationParams.hpp"
#include "engine/config/HomographyTrackerParams.hpp"
#include "engine/config/ParamSection.hpp"
#include "engine/config/PoseParams.hpp"
#include "engine/config/RansacParams.hpp"
#include "engine/config/ReferenceSelectionParams.hpp"
#include "engine/config/RelocalisationParams.hpp"
#include "engine/config/WideBaselineParams.hpp"

namespace reftrack {

enum class TrackingMode { SixDof, Homography };

// "6dof" / "homography"; parsing throws reftrack::Error listing the accepted names.
std::string toString(TrackingMode mode);
TrackingMode parseTrackingMode(const std::string& text);

struct TrackerParams : ParamSection<TrackerParams> {
  static constexpr const char* kSection = "";  // the file\'s root
  // Sections of the same file that other readers check (the viewer's `overlay`).
  inline static const std::vector<std::string> kOtherSections = {"overlay"};

  TrackingMode mode = TrackingMode::SixDof;
  CornerParams corners;
  CorrelationParams correlation;
  RansacParams ransac;
  HomographyTrackerParams homography;
  WideBaselineParams wideBaseline;
  PoseParams pose;
  RelocalisationParams relocalisation;
  ReferenceSelectionParams references;

  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
  void read(const YamlNode& root);  // root: the top-level map

  // Throws reftrack::Error naming the file, the line and the key at fault.
  static TrackerParams load(const std::filesystem::path& file);
  // The same from YAML text (JSON is YAML too); `what` names it in messages.
  static TrackerParams parse(const std::string& text, const std::string& what);
  void save(const std::filesystem::path& file) const;  // atomic (temp file + rename)
};
extern template struct ParamSection<TrackerParams>;  // defined in TrackerParams.cpp

}  // namespace reftrack
