#pragma once
// What `bench-real --suite` prints and writes: ONE table over every clip of the suite (a row per
// clip, order and method: frames, tracked and %, mean / p95 cube error, poses within 5 px, wrong
// poses (more than the clip's wrong_px off), reftrack's median true / predicted cube error,
// median thread CPU per frame), a legend line per clip above it (frames, references, cube, map
// and peer model sizes, where the peers' poses came from), and below it per order the clip where
// reftrack's mean is worst against its best peer's, the worst of the clips whose truth is
// sub-pixel (wrong_px <= 5), and last the worst of all.
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>

#include "app/research/sixdof/RealClipSuiteBenchmark.hpp"

namespace reftrack::app {

// reftrack's mean cube error over its best peer's in one clip and order (bestPeerRun: of the
// peers posing >= 90% of the frames the most accurate, else the one posing the most).
struct SuiteRatio {
  std::string clip, order, peer;
  double wrongPx = NAN;  // the clip's wrong_px
  double reftrackMeanPx = NAN, peerMeanPx = NAN;
  double ratio = NAN;  // reftrack / peer; +inf when reftrack posed no frame and the peer did
};

// Per (clip, order) with a reftrack run and a peer run with a mean: the ratio.
std::vector<SuiteRatio> suiteRatios(const RealClipSuiteResult& result);
// The largest ratio among `ratios` whose order is `order` ("" : any order) and whose clip's
// wrong_px is at most `maxWrongPx`; nullopt when none.
std::optional<SuiteRatio> worstRatio(const std::vector<SuiteRatio>& ratios,
                                     const std::string& order = "", double maxWrongPx = INFINITY);

std::string realClipSuiteTable(const RealClipSuiteResult& result);

struct RealClipSuiteFiles {
  std::filesystem::path table;                  // OUT/table.txt: the suite's table
  std::vector<std::filesystem::path> clipDirs;  // OUT/<clip>/: table.txt, cube_errors.csv, .png
};

// Writes OUT/<clip>/ for every clip run (writeGroundTruthBenchmarkFiles: its own detailed table,
// the per-frame CSV and the plot), then OUT/table.txt, each file atomically. Throws
// reftrack::Error when a folder or file cannot be written.
RealClipSuiteFiles writeRealClipSuiteFiles(const RealClipSuiteResult& result,
                                           const std::filesystem::path& folder);

}  // namespace reftrack::app
