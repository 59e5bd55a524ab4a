#pragma once
// ViewerState: everything the ImGui panels show and edit, owned by the viewer loop. Panels set
// requests (step, seek, start recording, ...); the loop carries them out and reports back.
#include <cstddef>
#include <optional>
#include <string>

#include "app/viewer/OverlayPanel.hpp"
#include "app/viewer/StatsHistory.hpp"
#include "app/viewer/ViewerSettings.hpp"

namespace reftrack::app {

struct SourceState {
  // Shown.
  std::string description;
  std::optional<int> frameCount;
  int currentIndex = -1;
  double fps = 30.0;
  bool seekable = false, live = false, ended = false;
  std::size_t droppedFrames = 0;
  // Edited.
  bool playing = true;
  bool loop = false;
  float speed = 1.0f;  // playback rate relative to the source's fps (window only)
  bool stepRequested = false;
  std::optional<int> seekRequest;
};

struct RecordState {
  std::string path = "recording.mp4";
  bool recording = false;
  bool startRequested = false, stopRequested = false;
  int framesWritten = 0;
  std::string message;  // last result or error
};

struct ViewerState {
  SourceState source;
  ViewerSettings settings;
  OverlayPanelEdit overlayEdit;
  std::string trackerName;
  bool trackerParamsChanged = false;  // set by the Tracking panel; the loop applies them
  std::string paramsPath = "reftrack_params.yml";
  std::string paramsMessage;
  std::string lastStatus;
  StatsHistory stats;
  RecordState record;
};

}  // namespace reftrack::app
