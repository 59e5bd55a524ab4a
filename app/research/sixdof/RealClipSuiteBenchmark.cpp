#include "app/research/sixdof/RealClipSuiteBenchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <set>

#include "app/research/sixdof/PeerPoseCache.hpp"
#include "app/sources/FrameSourceFactory.hpp"
#include "engine/core/Error.hpp"
#include "engine/dataset/DatasetGroundTruth.hpp"

namespace reftrack::app {

namespace fs = std::filesystem;

const std::vector<std::string>& defaultSuiteMethods() {
  static const std::vector<std::string> methods = {"reftrack", "sift", "akaze", "orb"};
  return methods;
}

const std::vector<std::string>& defaultSuiteOrders() {
  static const std::vector<std::string> orders = {"sequence", "shuffled-sequence"};
  return orders;
}

void RealClipSuiteOptions::check() const {
  GroundTruthBenchmarkOptions benchmark;  // its checks of the methods and orders
  benchmark.references = {0, 1};
  benchmark.methods = methods;
  benchmark.orders = orders;
  benchmark.peerPoses = [](const std::string&, const std::vector<int>&) { return PeerPoses{}; };
  benchmark.check();  // also refuses away:N (the replayed peers cover the clip's frames only)
  std::set<std::string> named;
  for (const std::string& clip : clips)
    if (!named.insert(clip).second) throw Error("bench-real: --clips: '" + clip + "' given twice");
}

RealClipSelection selectRealClips(const RealClipSuite& suite, const RealClipSuiteOptions& o) {
  if (!fs::is_directory(o.dataRoot))
    throw Error("data folder '" + o.dataRoot.string() +
                "' not found (--data DIR: the folder the suite's paths are relative to)");
  for (const std::string& name : o.clips)
    if (!suite.find(name)) {
      std::string known;
      for (const RealClip& clip : suite.clips) known += (known.empty() ? "" : ", ") + clip.name;
      throw Error("--clips: " + suite.description + " has no clip '" + name +
                  "' (its clips: " + known + ")");
    }
  RealClipSelection selection;
  for (const RealClip& clip : suite.clips) {
    if (!o.clips.empty() && std::find(o.clips.begin(), o.clips.end(), clip.name) == o.clips.end())
      continue;
    RealClipPlan plan{clip, o.dataRoot / clip.folder, {}, {}, {}};
    if (!fs::is_directory(plan.folder)) {
      selection.skipped.push_back(clip.name + ": its folder '" + plan.folder.string() +
                                  "' is missing");
      continue;
    }
    plan.frames = plan.folder / clip.frames;
    plan.camera = plan.folder / clip.camera;
    plan.groundTruth = plan.folder / clip.groundTruth;
    const std::string where = "clip '" + clip.name + "' (" + suite.description + ", line " +
                              std::to_string(clip.line) + "): ";
    if (!fs::exists(plan.frames))
      throw Error(where + "its frames '" + plan.frames.string() + "' are missing");
    if (!fs::is_regular_file(plan.camera))
      throw Error(where + "its camera '" + plan.camera.string() + "' is missing");
    if (!fs::is_regular_file(plan.groundTruth))
      throw Error(where + "its ground truth '" + plan.groundTruth.string() + "' is missing");
    try {  // cheap reads now, so a bad file stops the suite before its first clip runs
      PinholeCamera::load(plan.camera);
      loadGroundTruth(plan.groundTruth.string());
      const std::optional<int> count = openFrameSource(plan.frames.string())->frameCount();
      const int last = clip.lastFrame
                           ? *clip.lastFrame
                           : *std::max_element(clip.references.begin(), clip.references.end());
      if (count && last >= *count)
        throw Error("frame " + std::to_string(last) + " is beyond its " + std::to_string(*count) +
                    " frames");
    } catch (const Error& e) {
      throw Error(where + e.what());
    }
    selection.found.push_back(std::move(plan));
  }
  if (selection.found.empty()) {
    std::string why;
    for (const std::string& s : selection.skipped) why += "; " + s;
    throw Error("none of the suite's clips was found in '" + o.dataRoot.string() + "'" + why);
  }
  return selection;
}

RealClipSuiteResult runRealClipSuite(const RealClipSuite& suite, const RealClipSuiteOptions& o,
                                     const TrackerParams& params,
                                     const ReferencePreparerParams& prepareParams,
                                     const SuiteProgress& progress) {
  o.check();
  const auto start = std::chrono::steady_clock::now();
  const RealClipSelection selection = selectRealClips(suite, o);
  RealClipSuiteResult result;
  result.suiteDescription = suite.description;
  result.dataRoot = o.dataRoot;
  // The orders run: the suite's, and each clip's own (RealClip::orders) in first appearance.
  for (const RealClipPlan& plan : selection.found)
    for (const std::string& order : plan.clip.orders.empty() ? o.orders : plan.clip.orders)
      if (std::find(result.orders.begin(), result.orders.end(), order) == result.orders.end())
        result.orders.push_back(order);
  result.skipped = selection.skipped;
  result.peerCache = o.peerCache.has_value();
  const std::optional<PeerPoseCache> cache =
      o.peerCache ? std::optional<PeerPoseCache>(PeerPoseCache(*o.peerCache)) : std::nullopt;
  const std::size_t n = selection.found.size();
  for (std::size_t c = 0; c < n; ++c) {
    const RealClipPlan& plan = selection.found[c];
    const RealClip& clip = plan.clip;
    const std::string prefix =
        "clip " + std::to_string(c + 1) + " of " + std::to_string(n) + " (" + clip.name + "): ";
    const auto say = [&](const std::string& line) {
      if (progress) progress(prefix + line);
    };
    say("reading frames " + std::to_string(clip.firstFrame) + ".." +
        (clip.lastFrame ? std::to_string(*clip.lastFrame) : std::string("the last")) + " of " +
        plan.frames.string());
    GroundTruthSequenceSpec spec;
    spec.input = plan.frames.string();
    spec.camera = plan.camera.string();
    spec.groundTruth = plan.groundTruth.string();
    spec.firstFrame = clip.firstFrame;
    spec.frames = clip.frameCount();
    const GroundTruthSequence sequence = [&] {
      try {
        return loadGroundTruthSequence(spec);
      } catch (const Error& e) {
        throw Error("clip '" + clip.name + "': " + e.what());
      }
    }();

    RealClipRun run;
    run.clip = clip;
    run.peersFromCache = true;
    GroundTruthBenchmarkOptions b;
    for (int r : clip.references) b.references.push_back(r - clip.firstFrame);
    b.cubeCentre = clip.cubeBaseCentre;
    b.cubeEdge = clip.cubeEdge;
    b.cubeInFrontM = clip.cubeInFrontM;
    b.methods = o.methods;
    b.orders = clip.orders.empty() ? o.orders : clip.orders;
    b.shuffleSeed = o.shuffleSeed;
    b.mapFailureIsLoss = true;
    bool anyPeer = false;
    b.peerPoses = [&](const std::string& detector, const std::vector<int>& references) {
      anyPeer = true;
      const std::string name = perFramePnpPeerName(detector);
      const auto compute = [&] {
        return computePeerPoses(detector, sequence, references, [&](int done, int total) {
          say(name + ", every frame once (replayed in every order): " + std::to_string(done) +
              " of " + std::to_string(total) + " frames done");
        });
      };
      if (!cache) {
        run.peersFromCache = false;
        run.peerSources.push_back(name + ": computed");
        return compute();
      }
      PeerPoseInputs inputs;
      inputs.detector = detector;
      inputs.frameFiles =
          frameFilesOf(spec.input, sequence.firstFrame, static_cast<int>(sequence.frames.size()));
      for (int r : references) {
        inputs.references.push_back(sequence.firstFrame + r);
        inputs.referencePoses.push_back(*sequence.truth.at(static_cast<std::size_t>(r)));
      }
      inputs.camera = sequence.camera;
      bool fromCache = false;
      std::string why;
      PeerPoses poses = cache->getOrCompute(inputs, compute, fromCache, why);
      run.peersFromCache = run.peersFromCache && fromCache;
      run.peerSources.push_back(name + ": " + why);
      say(name + ": " + why);
      return poses;
    };
    try {
      run.benchmark = runGroundTruthBenchmark(sequence, b, params, prepareParams, say);
    } catch (const Error& e) {
      throw Error("clip '" + clip.name + "': " + e.what());
    }
    if (!anyPeer) run.peersFromCache = false;
    if (!run.benchmark.mapError.empty()) say("no map: " + run.benchmark.mapError);
    result.clips.push_back(std::move(run));
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace reftrack::app
