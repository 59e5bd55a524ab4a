#pragma once
// SimulatedSequence: everything a 6-DOF experiment needs from the simulator, made once and shared
// by every tracker run on it — the camera, the reference map prepared from the two marker-
// calibrated reference images (exactly as `reftrack prepare` does), the frames (grey) and the
// ground truth. Rendering needs a current GL context (render::createHeadlessContext()).
#include <filesystem>
#include <optional>
#include <vector>

#include "app/simulator/SimulationOptions.hpp"
#include "engine/config/RelocalisationParams.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/TumTrajectory.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "engine/reference/ReferencePreparer.hpp"

namespace reftrack::app {

struct SimulatedSequence {
  SimulationOptions options;
  PinholeCamera camera;
  Preparation preparation;  // map + report of references A and B (the paper's two)
  // All options.referenceCount() reference views (MultiReferencePreparer, marker poses, with the
  // keypoint layer), when asked for.
  std::optional<MultiReferenceMap> references;
  std::vector<cv::Mat> frames;  // CV_8UC1
  TumTrajectory groundTruth;    // camera in world, one entry per frame (timestamps k / fps)
};

class SceneSimulator;

// The map of the simulator's first `count` reference views (MultiReferencePreparer, posed by the
// marker as `reftrack prepare` does, with the keypoint layer of `keypoints`). Throws
// reftrack::Error when count is not in 2..the simulator's reference count.
MultiReferenceMap prepareSimulatedReferences(SceneSimulator& sim, int count,
                                             const ReferencePreparerParams& params = {},
                                             const RelocalisationParams& keypoints = {});

// Which reference maps a sequence is prepared with.
enum class SequenceMaps {
  TwoReferences,  // `preparation` only
  AllReferences,  // and `references`
};

// Renders the sequence (progress on stderr) and prepares the map(s) from the marker.
SimulatedSequence simulateSequence(const SimulationOptions& options,
                                   const ReferencePreparerParams& preparation = {},
                                   SequenceMaps maps = SequenceMaps::TwoReferences,
                                   const RelocalisationParams& keypoints = {});

// The sequence of `options` from a folder under `cacheDir` named after every option that changes
// the frames, when an earlier call stored it there (map, grey PNG frames, ground truth; the
// preparation report is not kept; the N-reference map in its own subfolder per reference count);
// otherwise simulated as above and stored. Repeated experiments then skip the rendering. Throws
// reftrack::Error when a stored folder is inconsistent.
SimulatedSequence cachedSimulatedSequence(const SimulationOptions& options,
                                          const std::filesystem::path& cacheDir,
                                          SequenceMaps maps = SequenceMaps::TwoReferences,
                                          const RelocalisationParams& keypoints = {});

}  // namespace reftrack::app
