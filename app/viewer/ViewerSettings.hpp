#pragma once
// ViewerSettings: the viewer's parameter file — the TrackerParams sections at the top level (so
// every command-line tool's `--params` accepts the same file) plus an `overlay` section, which
// the other tools ignore.
#include <filesystem>

#include "app/viewer/OverlaySettings.hpp"
#include "engine/config/TrackerParams.hpp"

namespace reftrack::app {

struct ViewerSettings {
  TrackerParams tracker;
  OverlaySettings overlay;

  void check() const;
  // Throws reftrack::Error naming the file and the key at fault.
  static ViewerSettings load(const std::filesystem::path& file);
  void save(const std::filesystem::path& file) const;  // atomic (temp file + rename)
};

}  // namespace reftrack::app
