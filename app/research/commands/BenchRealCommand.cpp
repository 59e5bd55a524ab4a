// `reftrack bench-real`: the 6-DOF tracker on real footage with ground truth, beside its peers
// measured in the same run. Three modes:
//  - `--suite FILE` (RealClipSuiteBenchmark): every clip of a suite file (the project's real
//    clips: app/research/suites/real-clips.yml) in order and shuffled as one sequence, reftrack
//    beside SIFT / AKAZE / ORB + PnP run once per clip (optionally from a peer cache): one table
//    over every clip, its last line the worst clip's reftrack mean over its best peer's.
//  - `--input` (GroundTruthBenchmark): any recording with a true pose per frame (an image folder
//    or video with a TUM file, tum:DIR, euroc:DIR), references taken from its frames: reftrack,
//    SIFT / AKAZE / ORB + PnP per frame and ORB + PnP + Kalman, in each --order (default: sequence
//    order and shuffled with cold starts; also shuffled-sequence, cuts:N, stride:K played as one
//    sequence): coverage, cube error, wrong poses, re-acquisition after cuts, thread CPU per frame;
//    table, CSV and plot.
//  - otherwise (RealFootageBenchmark): a clip of a card on a table, the truth from the card
//    (default ViSP's postcard clip): tracked %, grid and cube error against the card, median and
//    p90 thread CPU per tracked frame beside ORB + PnP + Kalman, and their ratio.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "app/commands/Commands.hpp"
#include "app/research/sixdof/GroundTruthBenchmark.hpp"
#include "app/research/sixdof/GroundTruthBenchmarkReport.hpp"
#include "app/research/sixdof/GroundTruthSequence.hpp"
#include "app/research/sixdof/RealClipSuite.hpp"
#include "app/research/sixdof/RealClipSuiteBenchmark.hpp"
#include "app/research/sixdof/RealClipSuiteReport.hpp"
#include "app/research/sixdof/RealFootageBenchmark.hpp"
#include "app/research/sixdof/SixDofRuns.hpp"
#include "app/sources/FrameSourceFactory.hpp"
#include "engine/core/Error.hpp"
#include "engine/evaluation/TrajectoryEvaluator.hpp"

namespace reftrack::app {

namespace {

struct BenchRealArgs {
  std::filesystem::path clip = "../shared/data/planar-videos/video-postcard.mp4";
  RealFootageOptions options = RealFootageOptions::postcard({});
  std::vector<float> target;  // --target: 8 numbers, or empty for the postcard's corners
  std::filesystem::path params, prepareParams, trajectory, framesCsv;
  // --input mode (GroundTruthBenchmark); passes: --passes when given, else 1.
  GroundTruthSequenceSpec sequence;
  GroundTruthBenchmarkOptions groundTruth;
  std::vector<double> cubeCentre = {0.0, 0.0, 0.0};
  std::string awayInput;  // away:N orders: the other scene (image folder, glob or video)
  int awayFrames = 300;   // ... at most this many of its frames are read
  std::filesystem::path out;
  // --suite mode (RealClipSuiteBenchmark); --methods, --order, --shuffle-seed go to `suite` when
  // given, else its defaults.
  std::filesystem::path suiteFile;
  RealClipSuiteOptions suite;
  std::string peerCache;
};

// The other scene of the away:N orders: up to `limit` frames of `input`, BGR.
std::vector<cv::Mat> readAwayFrames(const std::string& input, int limit) {
  const std::unique_ptr<FrameSource> source = openFrameSource(input);
  std::vector<cv::Mat> frames;
  while (static_cast<int>(frames.size()) < limit) {
    std::optional<Frame> frame = source->next();
    if (!frame) break;
    cv::Mat bgr = frame->image;
    if (bgr.channels() == 1) cv::cvtColor(bgr, bgr, cv::COLOR_GRAY2BGR);
    frames.push_back(bgr);
  }
  if (frames.empty()) throw Error("bench-real: --away-input '" + input + "' gave no frame");
  return frames;
}

void runGroundTruthMode(const BenchRealArgs& a) {
  cv::setNumThreads(1);
  GroundTruthBenchmarkOptions o = a.groundTruth;
  o.cubeCentre = Eigen::Vector3d(a.cubeCentre[0], a.cubeCentre[1], a.cubeCentre[2]);
  o.frames = a.options.frames;
  if (!a.awayInput.empty()) {
    o.awayFrames = readAwayFrames(a.awayInput, a.awayFrames);
    o.awayDescription = std::to_string(o.awayFrames.size()) + " frames of " + a.awayInput;
  }
  o.check();
  const TrackerParams params = a.params.empty() ? TrackerParams{} : TrackerParams::load(a.params);
  const ReferencePreparerParams prepareParams =
      a.prepareParams.empty() ? ReferencePreparerParams{}
                              : ReferencePreparerParams::load(a.prepareParams);
  GroundTruthSequenceSpec spec = a.sequence;
  // Every frame benchmarked, and the reference frames even when they lie beyond them.
  const int lastReference = *std::max_element(o.references.begin(), o.references.end());
  spec.frames = o.frames > 0 ? std::max(o.frames, lastReference + 1) : 0;
  const GroundTruthSequence sequence = loadGroundTruthSequence(spec);
  std::printf("%s: %zu frames read; camera: %s\n", sequence.framesDescription.c_str(),
              sequence.frames.size(), sequence.cameraDescription.c_str());
  std::fflush(stdout);
  const GroundTruthBenchmarkResult r = runGroundTruthBenchmark(
      sequence, o, params, prepareParams,
      [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); });
  std::printf("%s", groundTruthBenchmarkTable(r).c_str());
  if (!a.out.empty()) {
    const GroundTruthBenchmarkFiles files = writeGroundTruthBenchmarkFiles(r, a.out);
    std::printf("wrote the table %s, per-frame errors %s, plot %s\n", files.table.c_str(),
                files.csv.c_str(), files.plot.c_str());
  }
}

void runSuiteMode(const BenchRealArgs& a) {
  cv::setNumThreads(1);
  const RealClipSuite suite = loadRealClipSuite(a.suiteFile);
  RealClipSuiteOptions o = a.suite;
  if (!a.peerCache.empty()) o.peerCache = a.peerCache;
  // The data root and every clip's files, checked before the parameters and the first clip.
  for (const std::string& skipped : selectRealClips(suite, o).skipped)
    std::fprintf(stderr, "skipped clip %s\n", skipped.c_str());
  const TrackerParams params = a.params.empty() ? TrackerParams{} : TrackerParams::load(a.params);
  const ReferencePreparerParams prepareParams =
      a.prepareParams.empty() ? ReferencePreparerParams{}
                              : ReferencePreparerParams::load(a.prepareParams);
  const RealClipSuiteResult r =
      runRealClipSuite(suite, o, params, prepareParams,
                       [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); });
  std::printf("%s", realClipSuiteTable(r).c_str());
  if (!a.out.empty()) {
    const RealClipSuiteFiles files = writeRealClipSuiteFiles(r, a.out);
    std::printf("wrote the table %s and, per clip, its table, per-frame errors and plot in",
                files.table.c_str());
    for (const auto& dir : files.clipDirs) std::printf(" %s", dir.c_str());
    std::printf("\n");
  }
}

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
  a->groundTruth.cubeEdge = 0.1;
  CLI::App* sub = parent.add_subcommand(
      "bench-real",
      "6-DOF tracking of real footage with ground truth vs per-frame OpenCV peers and ORB + PnP + "
      "Kalman: cube error, coverage, wrong poses (also shuffled, cut or strided orders), thread "
      "CPU per frame; --suite: every real clip of a suite file in one table");
  // Either mode.
  CLI::Option* frames =
      sub->add_option("--frames", a->options.frames, "Frames benchmarked from the start (0: all)")
          ->check(CLI::Range(0, 1000000))
          ->capture_default_str();
  CLI::Option* passes =
      sub->add_option("--passes", a->options.passes,
                      "Passes over the frames for the timing (errors from the first; default 3 "
                      "for a card clip, 1 with --input)")
          ->check(CLI::Range(1, 100));
  sub->add_option("--params", a->params, "TrackerParams YAML")->check(CLI::ExistingFile);
  sub->add_option("--prepare-params", a->prepareParams, "`prepare --params` YAML for the map")
      ->check(CLI::ExistingFile);
  // Any recording with ground truth.
  CLI::Option* input = sub->add_option(
      "--input", a->sequence.input,
      "A recording with ground truth: image folder (frame k at k / 30 s), video, tum:DIR or "
      "euroc:DIR; selects this mode");
  CLI::Option* camera = sub->add_option("--camera", a->sequence.camera,
                                        "With --input: camera.yml (euroc: inputs bring theirs)");
  CLI::Option* gt = sub->add_option(
      "--gt", a->sequence.groundTruth,
      "With --input: TUM trajectory (camera in world), tum:DIR or euroc:DIR (default for "
      "tum:/euroc: inputs: their own)");
  CLI::Option* refFrames =
      sub->add_option("--ref-frames", a->groundTruth.references,
                      "With --input: frame indices of the references, posed by the ground truth "
                      "(>= 2), e.g. 0,40")
          ->delimiter(',')
          ->check(CLI::NonNegativeNumber);
  CLI::Option* cubeCentre =
      sub->add_option("--cube-centre", a->cubeCentre,
                      "With --input: x,y,z of the centre of the scored cube's base (world, m; the "
                      "cube extends to +z)")
          ->delimiter(',')
          ->expected(3)
          ->capture_default_str();
  CLI::Option* cubeEdge = sub->add_option("--cube-edge", a->groundTruth.cubeEdge,
                                          "With --input: the scored cube's edge (m)")
                              ->check(CLI::PositiveNumber)
                              ->capture_default_str();
  CLI::Option* shuffleSeed =
      sub->add_option("--shuffle-seed", a->groundTruth.shuffleSeed,
                      "With --input or --suite: seed of the shuffled orders (shuffled, "
                      "shuffled-sequence, cuts:N)")
          ->capture_default_str();
  CLI::Option* order =
      sub->add_option(
             "--order", a->groundTruth.orders,
             "With --input or --suite (default there: sequence,shuffled-sequence): frame orders "
             "to run every method in, comma-separated, of sequence, shuffled (every frame a "
             "cold start), shuffled-sequence (that order as one sequence, no reset), cuts:N (N "
             "contiguous segments in a shuffled order, one sequence; frames to re-acquire after "
             "each cut), stride:K (frames 0, K, 2K, ... in order; only those scored), away:N "
             "(--input only: in order, N frames of --away-input after the first half: poses "
             "there are wrong; the CPU spent there and the frames to re-acquire after the "
             "return), return:A-B+C-D+... (ranges of the clip's own frames played one after "
             "the other as one sequence, backwards when B < A, frames may repeat: the start, "
             "away, the return; every play scored; per range the plays to re-acquire; a suite "
             "clip may name its own orders)")
          ->delimiter(',')
          ->capture_default_str();
  CLI::Option* methods =
      sub->add_option("--methods", a->groundTruth.methods,
                      "With --input or --suite (default there: reftrack,sift,akaze,orb): methods "
                      "to run, of reftrack,sift,akaze,orb,kalman")
          ->delimiter(',')
          ->capture_default_str();
  CLI::Option* awayInput =
      sub->add_option("--away-input", a->awayInput,
                      "With --input and an away:N order: frames of another scene (image folder, "
                      "glob or video; resized to the input's size), played in turn");
  CLI::Option* awayFrames =
      sub->add_option("--away-frames", a->awayFrames,
                      "With --away-input: read at most this many of its frames")
          ->check(CLI::Range(1, 100000))
          ->capture_default_str();
  CLI::Option* out = sub->add_option(
      "--out", a->out,
      "With --input: folder for table.txt, cube_errors.csv and cube_errors.png; with --suite: "
      "table.txt (the suite's table) and per clip CLIP/table.txt, cube_errors.csv and "
      "cube_errors.png (written once every run is done)");
  for (CLI::Option* o : {camera, gt, refFrames, cubeCentre, cubeEdge, awayInput, awayFrames})
    o->needs(input);
  // Every real clip of a suite file.
  CLI::Option* suite =
      sub->add_option("--suite", a->suiteFile,
                      "A suite file of real clips with true poses (YAML; the project's: "
                      "app/research/suites/real-clips.yml); selects this mode");
  CLI::Option* data = sub->add_option("--data", a->suite.dataRoot,
                                      "With --suite: the folder the suite's paths are relative to")
                          ->capture_default_str();
  CLI::Option* clips =
      sub->add_option("--clips", a->suite.clips,
                      "With --suite: the clips to run, by name, comma-separated (default: all)")
          ->delimiter(',');
  CLI::Option* peerCache = sub->add_option(
      "--peer-cache", a->peerCache,
      "With --suite: a folder keeping the per-frame peers' poses between runs, keyed by "
      "everything they depend on (frame files' names, sizes and times, references and their "
      "poses, camera, method and its settings); default: no cache");
  for (CLI::Option* o : {data, clips, peerCache}) o->needs(suite);
  suite->excludes(input);
  // A card clip (the default mode).
  CLI::Option* clip = sub->add_option("--clip", a->clip,
                                      "Video of a card on a table (default: ViSP's postcard clip)")
                          ->capture_default_str();
  CLI::Option* references =
      sub->add_option("--references", a->options.references,
                      "Card clip: frame indices of the reference images, comma-separated (>= 2)")
          ->delimiter(',')
          ->check(CLI::NonNegativeNumber)
          ->capture_default_str();
  CLI::Option* target =
      sub->add_option("--target", a->target,
                      "Card clip: the card's corners in frame 0 to a few pixels: x,y of top-left, "
                      "top-right, bottom-right, bottom-left (default: the postcard clip's)")
          ->delimiter(',')
          ->expected(8);
  CLI::Option* targetWidth =
      sub->add_option("--target-width", a->options.targetTopEdgeMetres,
                      "Card clip: length of the card's top edge, metres (the world's scale)")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
  CLI::Option* focal =
      sub->add_option("--focal", a->options.focalPx,
                      "Card clip: focal length fx = fy in pixels, principal point at the centre "
                      "(the postcard clip has no calibration; ViSP assumes 840)")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
  CLI::Option* noBaseline = sub->add_flag("!--no-baseline", a->options.baseline,
                                          "Card clip: skip the ORB + PnP + Kalman baseline");
  CLI::Option* trajectory = sub->add_option(
      "--trajectory", a->trajectory,
      "Card clip: write reftrack's poses (TUM, world = the card; time = frame / fps)");
  CLI::Option* framesCsv = sub->add_option(
      "--frames-csv", a->framesCsv,
      "Card clip: write one CSV row per frame of reftrack's first pass: state, pair, grid and "
      "cube error, distance from each reference, matches, inliers, the card's corners and the "
      "truth's own corner shift (refined vs followed homography), message");
  for (CLI::Option* o :
       {clip, references, target, targetWidth, focal, noBaseline, trajectory, framesCsv}) {
    o->excludes(input);
    o->excludes(suite);
  }
  for (CLI::Option* o : {frames, passes}) o->excludes(suite);  // a suite's clips name their frames
  // Usage errors (exit 2): checked when the command line is parsed, before anything is read.
  sub->callback([a, input, passes, suite, methods, order, shuffleSeed, out] {
    if (suite->count() > 0) {
      if (methods->count() > 0) a->suite.methods = a->groundTruth.methods;
      if (order->count() > 0) a->suite.orders = a->groundTruth.orders;
      a->suite.shuffleSeed = a->groundTruth.shuffleSeed;
      try {
        a->suite.check();
      } catch (const Error& e) {
        throw CLI::ValidationError("bench-real", e.what());
      }
      return;
    }
    if (input->count() == 0)
      for (CLI::Option* o : {methods, order, shuffleSeed, out})
        if (o->count() > 0) throw CLI::ValidationError(o->get_name(), "needs --input or --suite");
    if (input->count() > 0) {
      if (passes->count() == 0) a->options.passes = 1;
      a->groundTruth.passes = a->options.passes;
      if (a->groundTruth.references.empty())
        throw CLI::RequiredError("--ref-frames (with --input)");
      GroundTruthBenchmarkOptions check = a->groundTruth;
      check.awayDescription = a->awayInput;
      try {
        check.check();
      } catch (const Error& e) {
        throw CLI::ValidationError("bench-real", e.what());
      }
      return;
    }
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
      "With --input: a map is prepared from the --ref-frames with their true poses (as `prepare\n"
      "--input --ref-frames --poses`); reftrack (MultiReferenceTracker), SIFT / AKAZE / ORB\n"
      "keypoints matched to the same references (triangulated with their poses) + solvePnPRansac\n"
      "+ solvePnPRefineLM per frame, and ORB + PnP + Kalman each run in every --order:\n"
      "  sequence           every frame in order\n"
      "  shuffled           every frame in a shuffled order (--shuffle-seed), each a cold start\n"
      "                     (the tracker reset, the Kalman filter restarted)\n"
      "  shuffled-sequence  the same shuffled order played as one sequence, no reset\n"
      "  cuts:N             the frames cut into N contiguous segments of about equal length,\n"
      "                     played in a shuffled order (no segment right after the one before it\n"
      "                     in time) as one sequence, no reset: N-1 cuts. A line per method gives\n"
      "                     each cut's frames to re-acquire (k: frames after the cut before the\n"
      "                     first pose within 1.5 px; 0: the first is good) and its wrong poses\n"
      "  stride:K           frames 0, K, 2K, ... in order as one sequence (fast motion); only\n"
      "                     those frames are scored\n"
      "Only `shuffled` resets a method between frames; the per-frame peers keep nothing anyway.\n"
      "cube: mean px distance of the cube's 8 vertices projected with K alone, estimated vs true\n"
      "pose; wrong: more than 5 px off; good: within 1.5 px. CPU: thread time per frame, one\n"
      "thread (cv::setNumThreads(1)). E.g. `--methods reftrack --order\n"
      "sequence,shuffled-sequence,cuts:8,stride:4` for reftrack alone (the peers take ~100 ms a\n"
      "frame).\n"
      "With --suite FILE: every clip of the suite file (YAML, e.g.\n"
      "app/research/suites/real-clips.yml: per clip its folder under --data, frame range,\n"
      "references, scored cube and wrong_px) runs as with --input, in every --order (default\n"
      "sequence,shuffled-sequence) with --methods (default reftrack,sift,akaze,orb). The "
      "per-frame\n"
      "peers pose each clip's frames once and those poses are reused in every order;\n"
      "--peer-cache DIR keeps them between runs. One table: per clip, order and method the\n"
      "frames, tracked, mean and p95 cube error, poses within 5 px, wrong poses (more than the\n"
      "clip's wrong_px off), reftrack's median true / predicted cube error and ms per frame; the\n"
      "last line: the worst clip's reftrack mean over its best peer's. A clip whose folder is\n"
      "missing is skipped and named; none found is an error.\n"
      "Card clip (no --input), ground truth (PlanarTargetTruth): the card's corners are\n"
      "followed from frame 0 by the homography tracker and refined by cornerSubPix; IPPE on them\n"
      "gives each frame's pose, the card's plane being the world. The map is prepared from the\n"
      "reference frames with those poses (as `prepare --poses`) and the clip tracked by the\n"
      "MultiReferenceTracker. grid: mean px distance of a 7x7 grid over the card from where the\n"
      "followed homography puts it; cube: a cube (0.1 m) on the card's centre against its\n"
      "projection through the card's pose. Speed: thread CPU per tracked frame, one thread\n"
      "(cv::setNumThreads(1)); each pass runs both trackers in turn. Stage times are wall clock,\n"
      "first pass.");
  return {sub, [a, input, suite] {
            if (suite->count() > 0) {
              runSuiteMode(*a);
              return;
            }
            if (input->count() > 0) {
              runGroundTruthMode(*a);
              return;
            }
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
