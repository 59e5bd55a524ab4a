#pragma once
// What `bench-real --input` shows and writes of a GroundTruthBenchmarkResult: the table (the
// recording, references, map and peer model sizes, the orders, then one row per method and order:
// coverage, mean / p95 / max cube error, poses more than 5 px off and within 1.5 px, median thread
// CPU per frame and its ratio to reftrack's in the same order; for cuts:N a line per method with
// each cut's frames to re-acquire and wrong poses; then why frames got no pose), a CSV of every
// frame's cube error per method and order, and a PNG of the first order's errors per frame:
// reftrack's beside the best peer's.
#include <filesystem>
#include <optional>
#include <string>

#include "app/research/sixdof/GroundTruthBenchmark.hpp"

namespace reftrack::app {

// The plot draws errors above its cap at the cap (the CSV keeps them), so sub-pixel differences
// stay visible beside a peer's outliers: 1.5 x the larger p95 of the two runs drawn, rounded up
// to a whole pixel, within these.
inline constexpr double kPlotErrorCapMinPx = 2.0;
inline constexpr double kPlotErrorCapMaxPx = 10.0;

// The best peer in `order` (index into result.runs), nullopt when no other method ran there: of
// the peers that posed at least 90% of the scored frames the one with the lowest mean cube error,
// else the one that posed the most.
std::optional<std::size_t> bestPeerRun(const GroundTruthBenchmarkResult& result,
                                       const std::string& order);

// The scored cube in words: "base centre (x, y, z) m, edge E m", or where it stands in front of
// the first reference's camera.
std::string cubeDescription(const GroundTruthBenchmarkResult& result);

// Whether a method that needs reftrack's map ran (reftrack, the Kalman baseline): else no map
// was prepared.
bool usesMap(const GroundTruthBenchmarkResult& result);

std::string groundTruthBenchmarkTable(const GroundTruthBenchmarkResult& result);

// The lines of a return: run (empty for other orders): per range its plays posed, within 5 px,
// more than `wrongPx` off, the plays to the first pose within 5 px and the CPU per frame; then
// the frames between the start and the return (posed, wrong, CPU and its share of one core at
// `fps`) and how the return was re-acquired. `firstFrame`: the input's index of frame 0.
std::string returnLines(const MethodRun& run, double fps, double wrongPx, int firstFrame);

// Per run with recovery counts (reftrack): what stopped each start near a reference and each
// relocalisation attempt, and the attempts' median thread CPU; each line starts with `prefix`.
std::string stopLines(const std::vector<MethodRun>& runs, const std::string& prefix);

// Header `frame,true_pose,<method>_<order>_px...`, then `<method>_<order>_predicted_px` for the
// runs with a predicted error (reftrack); one row per frame (frame: the input's index); an empty
// cell: no pose (or no prediction); inf: the pose put the whole cube behind the camera.
void writeGroundTruthBenchmarkCsv(const GroundTruthBenchmarkResult& result,
                                  const std::filesystem::path& csv);
void writeGroundTruthBenchmarkPlot(const GroundTruthBenchmarkResult& result,
                                   const std::filesystem::path& png);

struct GroundTruthBenchmarkFiles {
  std::filesystem::path table, csv, plot;
};

// Writes table.txt, cube_errors.csv and cube_errors.png into `folder` (created if needed), each
// atomically; returns their paths. Throws reftrack::Error when one cannot be written.
GroundTruthBenchmarkFiles writeGroundTruthBenchmarkFiles(const GroundTruthBenchmarkResult& result,
                                                         const std::filesystem::path& folder);

}  // namespace reftrack::app
