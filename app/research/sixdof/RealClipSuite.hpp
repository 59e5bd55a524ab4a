#pragma once
// RealClipSuite: the real clips with true poses that `bench-real --suite FILE` runs (the
// project's is app/research/suites/real-clips.yml), read with the strict YAML reader of every
// user file (ConfigFile: an unknown key, a value of the wrong type or a missing one is an error
// naming its line). Paths are relative to a data root (`--data`):
//   clips:
//     - name: kinect-kitchen-180-300   # unique; letters, digits, '.', '_', '-'
//       folder: kinect-kitchen          # the clip's folder in the data root
//       frames: frames                  # in the folder: an image folder or a video (default)
//       camera: camera.yml              # in the folder (default)
//       ground_truth: groundtruth.txt   # in the folder: TUM, camera in world (default)
//       first_frame: 180                # the frames benchmarked, input frame indices, both
//       last_frame: 300                 #   inclusive (default: every frame)
//       references: [200, 220]          # input frame indices within the range, >= 2, distinct
//       cube: {edge: 0.08, in_front_of_reference: {distance: 1.0}}  # or base_centre: [x, y, z]
//       wrong_px: 20                    # a pose more than this off is wrong
//       orders: [return:0-70+110-150+70-0]  # optional: this clip's frame orders instead of
//                                       #   the suite's (--order); no away:N
#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace reftrack::app {

struct RealClip {
  std::string name;
  int line = 0;                  // where the clip starts in the suite file
  std::filesystem::path folder;  // in the data root
  std::filesystem::path frames = "frames", camera = "camera.yml",
                        groundTruth = "groundtruth.txt";  // in the folder
  int firstFrame = 0;
  std::optional<int> lastFrame;  // none: to the last frame
  std::vector<int> references;   // input frame indices
  double cubeEdge = 0.1;
  Eigen::Vector3d cubeBaseCentre = Eigen::Vector3d::Zero();  // world, m (cubeInFrontM == 0)
  double cubeInFrontM = 0.0;  // > 0: centred this far in front of the first reference's camera
  double wrongPx = 5.0;
  std::vector<std::string> orders;  // its own frame orders (`--order` names); empty: the suite's

  // Frames benchmarked (last - first + 1), 0 when the range runs to the end.
  int frameCount() const { return lastFrame ? *lastFrame - firstFrame + 1 : 0; }
};

struct RealClipSuite {
  std::string description;  // the file, as named in messages
  std::vector<RealClip> clips;

  const RealClip* find(const std::string& name) const;  // nullptr when there is none
};

// Throws reftrack::Error "suite file 'FILE' ..." when the file is missing or unreadable, and
// "suite file 'FILE': line N: ..." for what is wrong in it: not YAML, an unknown key (with the
// nearest known one), a missing or mistyped value, no clips, a name given twice, a range with
// last_frame < first_frame, references outside the range, fewer than two or one given twice,
// both or neither cube placement, a non-positive edge, distance or wrong_px, an absolute path, an
// unknown or away:N order, or a return: range beyond the clip's frames.
RealClipSuite loadRealClipSuite(const std::filesystem::path& file);
// The same for the text of a suite file; `what` names it in messages.
RealClipSuite parseRealClipSuite(const std::string& text, const std::string& what);

}  // namespace reftrack::app
