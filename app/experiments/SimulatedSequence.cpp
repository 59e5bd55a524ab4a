#include "app/experiments/SimulatedSequence.hpp"

#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "app/cli/ProgressBar.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "engine/core/Error.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack::app {

SimulatedSequence simulateSequence(const SimulationOptions& options,
                                   const ReferencePreparerParams& preparation) {
  options.check();
  SimulatedSequence s;
  s.options = options;
  SceneSimulator sim(options);
  s.camera = sim.camera();
  const ReferenceImage a{sim.renderReference('A'), "simulated reference A"};
  const ReferenceImage b{sim.renderReference('B'), "simulated reference B"};
  s.preparation = ReferencePreparer(s.camera, preparation).prepare(a, b, sim.marker());
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
      << "_fps" << o.fps;
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
                                          const std::filesystem::path& cacheDir) {
  options.check();
  const fs::path dir = cacheDir / cacheKey(options);
  if (fs::exists(dir / "groundtruth.txt")) return load(options, dir);
  SimulatedSequence s = simulateSequence(options);
  store(s, dir);
  return s;
}

}  // namespace reftrack::app
