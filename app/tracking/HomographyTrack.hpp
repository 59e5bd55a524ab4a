#pragma once
// `reftrack track --mode homography`: registers every frame of a source to a reference image
// (HomographyTracker, paper Sec. 7.3) and writes the per-frame CSV (HomographyTrackCsv.hpp) and,
// optionally, an MP4 of the frames with the reference outline and the labels at their mapped
// positions. Called by TrackCommand for the homography mode.
#include <filesystem>
#include <string>

namespace reftrack::app {

struct HomographyTrackOptions {
  std::filesystem::path reference;  // the stored frame (image file)
  std::string input;                // video file, image folder/glob, camera:N, sim:PRESET
  std::filesystem::path labels;     // optional AnnotationSet YAML
  std::filesystem::path camera;     // optional camera.yml of the frames' camera (K: rotation-only
                                    // model for a reference of its size; lens distortion)
  std::filesystem::path params;     // optional TrackerParams YAML
  std::filesystem::path csv;        // per-frame CSV; empty = none
  std::filesystem::path record;     // MP4 of the registered overlay; empty = none
  int maxFrames = -1;               // -1 = all
  bool debugOverlay = false;        // the recording also shows corners, matches, status label
};

struct HomographyTrackSummary {
  int frames = 0;
  int tracked = 0;
  double medianMs = 0.0;
  std::string advice;  // NonPlanarAdvice's message when it was shown during the clip
};

// The reference and the frames may have different sizes (another camera). Throws
// reftrack::Error on bad input (unreadable reference, a first frame of another size than the
// camera's, bad labels or params); nothing is written then.
HomographyTrackSummary runHomographyTrack(const HomographyTrackOptions& options);

}  // namespace reftrack::app
