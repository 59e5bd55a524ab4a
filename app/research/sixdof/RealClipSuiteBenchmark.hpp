#pragma once
// RealClipSuiteBenchmark (`bench-real --suite`): every clip of a RealClipSuite run through the
// GroundTruthBenchmark in turn: its frame range read (GroundTruthSequence), a map prepared from
// its references with their true poses, reftrack in every frame order, and the per-frame peers
// (SIFT / AKAZE / ORB + PnP) run once per clip and replayed in every order (a per-frame peer gives
// a frame the same pose in any order), from a PeerPoseCache when one is given. A clip whose folder
// is missing from the data root is skipped (and named); a missing data root, no clip found, or a
// clip whose files are missing or wrong is an error before anything runs (the frames themselves
// are read when the clip's turn comes).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/research/sixdof/GroundTruthBenchmark.hpp"
#include "app/research/sixdof/RealClipSuite.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/reference/ReferencePreparer.hpp"

namespace reftrack::app {

// The suite's defaults: reftrack beside the three per-frame peers, in order and shuffled as one
// sequence.
const std::vector<std::string>& defaultSuiteMethods();  // reftrack sift akaze orb
const std::vector<std::string>& defaultSuiteOrders();   // sequence shuffled-sequence

struct RealClipSuiteOptions {
  std::filesystem::path dataRoot = "../shared/data";
  std::vector<std::string> methods = defaultSuiteMethods();  // `--methods` names
  std::vector<std::string> orders = defaultSuiteOrders();    // `--order` names (no away:N)
  std::vector<std::string> clips;  // the clips run, by name, in suite order; empty: every clip
  std::optional<std::filesystem::path> peerCache;  // PeerPoseCache folder; none: no cache
  std::uint64_t shuffleSeed = 1;

  // Throws reftrack::Error naming the bad option: an unknown or repeated method or order, an
  // away:N order, a clip name given twice.
  void check() const;
};

struct RealClipRun {
  RealClip clip;
  GroundTruthBenchmarkResult benchmark;
  std::vector<std::string> peerSources;  // per peer run: "SIFT+PnP: cached in ..." / "computed"
  bool peersFromCache = false;           // every peer's poses came from the cache
};

struct RealClipSuiteResult {
  std::string suiteDescription;
  std::filesystem::path dataRoot;
  std::vector<std::string> orders;   // as run
  std::vector<RealClipRun> clips;    // in suite order
  std::vector<std::string> skipped;  // "NAME: its folder DIR is missing", in suite order
  bool peerCache = false;            // a cache was used
  double seconds = 0.0;              // wall clock of the whole run
};

// One clip whose folder exists, ready to run: its files in the data root.
struct RealClipPlan {
  RealClip clip;
  std::filesystem::path folder, frames, camera, groundTruth;
};

// The clips of `suite` the options select, split into those found and those skipped. Throws
// reftrack::Error when the data root is missing, a named clip is not in the suite, no selected
// clip's folder exists, or a found clip lacks its frames, camera or ground truth.
struct RealClipSelection {
  std::vector<RealClipPlan> found;
  std::vector<std::string> skipped;  // as RealClipSuiteResult::skipped
};
RealClipSelection selectRealClips(const RealClipSuite& suite, const RealClipSuiteOptions& options);

// Progress lines for the caller to print (stderr), each starting "clip k of n (NAME): ".
using SuiteProgress = std::function<void(const std::string&)>;

// Runs the found clips in turn (cv::setNumThreads(1) is the caller's). Throws reftrack::Error as
// selectRealClips does, and when a clip's frames cannot be read or do not fit its camera.
RealClipSuiteResult runRealClipSuite(const RealClipSuite& suite,
                                     const RealClipSuiteOptions& options,
                                     const TrackerParams& params,
                                     const ReferencePreparerParams& prepareParams,
                                     const SuiteProgress& progress = {});

}  // namespace reftrack::app
