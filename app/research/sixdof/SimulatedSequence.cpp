#include "app/research/sixdof/SimulatedSequence.hpp"

#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "app/cli/ProgressBar.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "engine/core/Error.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "engine/reference/MultiReferencePreparer.hpp"
#include "engine/relocalisation/ReferenceKeypointBuilder.hpp"

namespace reftrack::app {

MultiReferenceMap prepareSimulatedReferences(SceneSimulator& sim, int count,
                                             const ReferencePreparerParams& params,
                                             const RelocalisationParams& keypoints) {
  const int available = static_cast<int>(sim.referencePoses().size());
  if (count < 2 || count > available)
    throw Error("simulated references: asked for " + std::to_string(count) + " of " +
                std::to_string(available) + " reference views");
  std::vector<ReferenceImage> images;
  for (int i = 0; i < count; ++i)
    images.push_back({sim.renderReferenceView(i), "simulated reference " + std::to_string(i)});
  MultiReferenceMap map =
      MultiReferencePreparer(sim.camera(), params).prepare(images, sim.marker()).map;
  buildReferenceKeypoints(map, keypoints);
  return map;
}

SimulatedSequence simulateSequence(const SimulationOptions& options,
                                   const ReferencePreparerParams& preparation, SequenceMaps maps,
                                   const RelocalisationParams& keypoints) {
  options.check();
  SimulatedSequence s;
  s.options = options;
  SceneSimulator sim(options);
  s.camera = sim.camera();
  const ReferenceImage a{sim.renderReference('A'), "simulated reference A"};
  const ReferenceImage b{sim.renderReference('B'), "simulated reference B"};
  s.preparation = ReferencePreparer(s.camera, preparation).prepare(a, b, sim.marker());
  if (maps == SequenceMaps::AllReferences)
    s.references =
        prepareSimulatedReferences(sim, options.referenceCount(), preparation, keypoints);
  ProgressBar progress("render " + options.preset, static_cast<std::size_t>(options.frames));
  for (int k = 0; k < options.frames; ++k) {
    cv::Mat gray;
    cv::cvtColor(sim.renderFrame(k), gray, cv::COLOR_BGR2GRAY);
    s.frames.push_back(gray);
    s.groundTruth.poses.push_back({k / options.fps, sim.framePose(k)});
    progress.advance();
  }
  progress.finish();
  return s;
}

namespace {

namespace fs = std::filesystem;

std::string cacheKey(const SimulationOptions& o) {
  std::ostringstream key;
  key << o.preset << "_" << o.frames << "f_" << o.size.width << "x" << o.size.height << "_seed"
      << o.seed << "_noise" << o.noiseSigma << (o.blur ? "_blur" : "") << "_fov" << o.fovDeg
      << "_fps" << o.fps << o.effects.key();
  for (std::size_t i = 0; i < o.distortion.size(); ++i)
    key << (i ? "," : "_dist") << o.distortion[i];
  if (o.referenceBaseline > 0.0) key << "_baseline" << o.referenceBaseline;
  return key.str();
}

fs::path framePath(const fs::path& dir, int k) {
  char name[32];
  std::snprintf(name, sizeof name, "%06d.png", k);
  return dir / "frames" / name;
}

void store(const SimulatedSequence& s, const fs::path& dir) {
  fs::create_directories(dir / "frames");
  MultiReferenceMap::fromPair(s.preparation.map).save(dir / "map");
  const std::vector<int> png = {cv::IMWRITE_PNG_COMPRESSION, 1};
  for (std::size_t k = 0; k < s.frames.size(); ++k) {
    const fs::path file = framePath(dir, static_cast<int>(k));
    if (!cv::imwrite(file.string(), s.frames[k], png))
      throw Error("cannot write cached frame '" + file.string() + "'");
  }
  s.groundTruth.save(dir / "groundtruth.txt");  // last: its presence marks a complete folder
}

SimulatedSequence load(const SimulationOptions& options, const fs::path& dir) {
  SimulatedSequence s;
  s.options = options;
  s.preparation.map = MultiReferenceMap::load(dir / "map").pair(0, 1);
  s.camera = s.preparation.map.camera;
  s.groundTruth = TumTrajectory::load(dir / "groundtruth.txt");
  if (static_cast<int>(s.groundTruth.poses.size()) != options.frames)
    throw Error("cached sequence '" + dir.string() + "' holds " +
                std::to_string(s.groundTruth.poses.size()) + " poses, expected " +
                std::to_string(options.frames) + "; delete the folder to re-simulate");
  for (int k = 0; k < options.frames; ++k) {
    const fs::path file = framePath(dir, k);
    cv::Mat gray = cv::imread(file.string(), cv::IMREAD_GRAYSCALE);
    if (gray.empty() || gray.size() != options.size)
      throw Error("cached frame '" + file.string() +
                  "' is missing or of another size; delete the folder to re-simulate");
    s.frames.push_back(std::move(gray));
  }
  return s;
}

}  // namespace

SimulatedSequence cachedSimulatedSequence(const SimulationOptions& options,
                                          const std::filesystem::path& cacheDir, SequenceMaps maps,
                                          const RelocalisationParams& keypoints) {
  options.check();
  const fs::path dir = cacheDir / cacheKey(options);
  // The N-reference map does not change the frames: one subfolder per reference count.
  const fs::path referencesDir = dir / ("references_" + std::to_string(options.referenceCount()));
  if (fs::exists(dir / "groundtruth.txt")) {
    SimulatedSequence s = load(options, dir);
    if (maps == SequenceMaps::AllReferences) {
      if (fs::exists(referencesDir / MultiReferenceMap::kFileName)) {
        s.references = MultiReferenceMap::load(referencesDir);
        // Stored without a keypoint layer, or with another kind: built now and stored again.
        bool layered = s.references->keypointKind == keypoints.keypoints;
        for (const ReferenceView& v : s.references->views)
          layered = layered && !v.keypoints.empty();
        if (!layered) {
          buildReferenceKeypoints(*s.references, keypoints);
          s.references->save(referencesDir);
        }
      } else {
        SceneSimulator sim(options);
        s.references = prepareSimulatedReferences(sim, options.referenceCount(), {}, keypoints);
        s.references->save(referencesDir);
      }
    }
    return s;
  }
  SimulatedSequence s = simulateSequence(options, {}, maps, keypoints);
  store(s, dir);
  if (s.references) s.references->save(referencesDir);
  return s;
}

}  // namespace reftrack::app
