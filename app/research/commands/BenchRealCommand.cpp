// `reftrack bench-real`: the 6-DOF tracker on a real clip with a prepared map and ground truth
// from a card on the table (RealFootageBenchmark): tracked %, grid and cube error against the
// card, median and p90 thread CPU per tracked frame, beside the ORB + solvePnPRansac +
// KalmanFilter baseline measured in the same run, and their ratio.
#include <cmath>
#include <cstdio>
#include <memory>
#include <opencv2/core/utility.hpp>

#include "app/commands/Commands.hpp"
#include "app/research/sixdof/RealFootageBenchmark.hpp"
#include "app/research/sixdof/SixDofRuns.hpp"
#include "engine/core/Error.hpp"
#include "engine/evaluation/TrajectoryEvaluator.hpp"

namespace reftrack::app {

namespace {

struct BenchRealArgs {
  std::filesystem::path clip = "../shared/data/planar-videos/video-postcard.mp4";
  RealFootageOptions options = RealFootageOptions::postcard({});
  std::vector<float> target;  // --target: 8 numbers, or empty for the postcard's corners
  std::filesystem::path params, prepareParams, trajectory, framesCsv;
};

void printRun(const RealFootageRun& r) {
  const ErrorStats grid = ErrorStats::of(r.gridErrorPx), cube = ErrorStats::of(r.cubeErrorPx);
  std::printf("%-18s %6d/%-4d %6.1f%% %9.3f %9.3f %9.3f %9.3f %10.2f %10.2f\n", r.name.c_str(),
              r.tracked, r.frames, r.trackedPercent(), grid.count ? grid.mean : NAN,
              grid.count ? grid.p95 : NAN, cube.count ? cube.mean : NAN,
              cube.count ? cube.p95 : NAN, percentileOf(r.trackedCpuMs, 0.5),
              percentileOf(r.trackedCpuMs, 0.9));
  for (const auto& [reason, frames] : r.noPose)
    std::printf("  no pose: %d x %s\n", frames, reason.c_str());
}

CommandRegistration registerBenchRealCommand(CLI::App& parent) {
  auto a = std::make_shared<BenchRealArgs>();
  CLI::App* sub = parent.add_subcommand(
      "bench-real",
      "6-DOF tracking of a real clip with a prepared map vs ORB + PnP + Kalman: error against a "
      "card's ground truth and thread CPU per tracked frame");
  sub->add_option("--clip", a->clip, "Video of a card on a table (default: ViSP's postcard clip)")
      ->capture_default_str();
  sub->add_option("--frames", a->options.frames, "Frames tracked from the start (0: all)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  sub->add_option("--references", a->options.references,
                  "Frame indices of the reference images, comma-separated (>= 2)")
      ->delimiter(',')
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  sub->add_option("--passes", a->options.passes,
                  "Tracking passes over the clip for the timing (each tracker fresh; errors from "
                  "the first)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  sub->add_option("--target", a->target,
                  "The card's corners in frame 0 to a few pixels: x,y of top-left, top-right, "
                  "bottom-right, bottom-left (default: the postcard clip's)")
      ->delimiter(',')
      ->expected(8);
  sub->add_option("--target-width", a->options.targetTopEdgeMetres,
                  "Length of the card's top edge, metres (the world's scale)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--focal", a->options.focalPx,
                  "Focal length fx = fy in pixels, principal point at the centre (the postcard "
                  "clip has no calibration; ViSP assumes 840)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--params", a->params, "TrackerParams YAML")->check(CLI::ExistingFile);
  sub->add_option("--prepare-params", a->prepareParams, "`prepare --params` YAML for the map")
      ->check(CLI::ExistingFile);
  sub->add_flag("!--no-baseline", a->options.baseline, "Skip the ORB + PnP + Kalman baseline");
  sub->add_option("--trajectory", a->trajectory,
                  "Write reftrack's poses (TUM, world = the card; time = frame / fps)");
  sub->add_option("--frames-csv", a->framesCsv,
                  "Write one CSV row per frame of reftrack's first pass: state, pair, grid and "
                  "cube error, distance from each reference, matches, inliers, the card's corners "
                  "and the truth's own corner shift (refined vs followed homography), message");
  // Usage errors (exit 2): checked when the command line is parsed, before anything is read.
  sub->callback([a] {
    const std::vector<int>& refs = a->options.references;
    if (refs.size() < 2)
      throw CLI::ValidationError("--references", "at least two reference frames are needed");
    for (std::size_t i = 0; i < refs.size(); ++i)
      for (std::size_t j = i + 1; j < refs.size(); ++j)
        if (refs[i] == refs[j])
          throw CLI::ValidationError("--references",
                                     "frame " + std::to_string(refs[i]) + " is given twice");
  });
  sub->footer(
      "Ground truth (PlanarTargetTruth): the card's corners are followed from frame 0 by the\n"
      "homography tracker and refined by cornerSubPix; IPPE on them gives each frame's pose, the\n"
      "card's plane being the world. The map is prepared from the reference frames with those\n"
      "poses (as `prepare --poses`) and the clip tracked by the MultiReferenceTracker. grid: mean\n"
      "px distance of a 7x7 grid over the card from where the followed homography puts it; cube:\n"
      "a cube (0.1 m) on the card's centre against its projection through the card's pose. Speed:\n"
      "thread CPU per tracked frame, one thread (cv::setNumThreads(1)); each pass runs both\n"
      "trackers in turn. Stage times are wall clock, first pass.");
  return {sub, [a] {
            cv::setNumThreads(1);
            RealFootageOptions o = a->options;
            o.clip = a->clip;
            if (!a->target.empty())
              for (std::size_t i = 0; i < 4; ++i)
                o.targetCorners[i] = cv::Point2f(a->target[2 * i], a->target[2 * i + 1]);
            const TrackerParams params =
                a->params.empty() ? TrackerParams{} : TrackerParams::load(a->params);
            const ReferencePreparerParams prepareParams =
                a->prepareParams.empty() ? ReferencePreparerParams{}
                                         : ReferencePreparerParams::load(a->prepareParams);
            const RealFootageResult r = runRealFootageBenchmark(o, params, prepareParams);
            if (!a->trajectory.empty()) r.reftrack.estimate.save(a->trajectory);
            if (!a->framesCsv.empty()) writeRealFootageFramesCsv(r.reftrack, a->framesCsv);
            std::printf(
                "%s: %d frames read, %dx%d; card followed in %d, aspect %.3f (PnP RMS %.2f px)\n",
                o.clip.string().c_str(), r.clipFrames, r.frameSize.width, r.frameSize.height,
                r.followedFrames, r.aspectRatio, r.aspectRms);
            std::printf("map: %zu references (frames", o.references.size());
            for (std::size_t i = 0; i < o.references.size(); ++i)
              std::printf(" %d (%.1f mm)", o.references[i], r.referenceBaselinesMm[i]);
            std::printf("), %d points; %d pass(es)\n", r.mapPoints, o.passes);
            std::printf("%-18s %11s %7s %9s %9s %9s %9s %10s %10s\n", "tracker", "tracked", "",
                        "grid_mean", "grid_p95", "cube_mean", "cube_p95", "cpu_ms_med",
                        "cpu_ms_p90");
            printRun(r.reftrack);
            if (r.baseline) printRun(*r.baseline);
            std::printf("rolling-shutter readout (reftrack, last tracked frame): %.3f\n",
                        r.rollingShutterReadout);
            std::printf("per-stage median ms (wall, reftrack):");
            for (const auto& [stage, ms] : r.reftrack.stageMs)
              std::printf("  %s %.3f", stage.c_str(), median(ms));
            std::printf("\n");
            if (r.baseline) {
              const double ours = percentileOf(r.reftrack.trackedCpuMs, 0.5);
              const double theirs = percentileOf(r.baseline->trackedCpuMs, 0.5);
              std::printf(
                  "speed ratio baseline / reftrack (median thread CPU per tracked frame): %.2f\n",
                  theirs / ours);
            }
          }};
}

const CommandRegistrar registrar(86, registerBenchRealCommand, CommandGroup::Research);

}  // namespace

}  // namespace reftrack::app
