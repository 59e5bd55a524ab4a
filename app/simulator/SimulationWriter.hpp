#pragma once
// writeSimulation: writes a simulated sequence to `outDir`:
//   frames/000000.png ...   BGR frames (each written atomically: temporary name + rename)
//   camera.yml              intrinsics (PinholeCamera::save)
//   reference_00.png ... reference_NN.png  the options.referenceCount() reference views, and
//   references.txt          their poses (TUM, camera in world; view i at timestamp i)
//   reference_a.png, reference_b.png  views 0 and 1 again (the two-reference layout)
//   scene.yml               world frame, marker, preset, seed, fps, frame count, image size
//   groundtruth.txt         TUM camera-in-world pose per frame, timestamp k / fps; written last,
//                           so a folder holding it is complete
// Stale frames and reference views of a longer earlier run in the same folder are removed. Progress
// on stderr.
#include <filesystem>

#include "app/simulator/SceneSimulator.hpp"

namespace reftrack::app {

void writeSimulation(SceneSimulator& sim, const std::filesystem::path& outDir);

}  // namespace reftrack::app
