// `reftrack experiment-6dof`: the 6-DOF tracker on a simulated sequence against
// exact ground truth — standard least squares (Eq. 12) and the regulariser (Eq.
// 13) on the very same frames, beside the ORB + solvePnPRansac + KalmanFilter
// baseline — printing accuracy, drift, jitter and per-stage median milliseconds
// with ratios, and plotting the cube error over time and the motion components
// (paper Fig. 13).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <opencv2/core/utility.hpp>

#include "app/cli/CameraEffectsValidator.hpp"
#include "app/cli/DistortionOption.hpp"
#include "app/cli/ImageSizeValidator.hpp"
#include "app/commands/Commands.hpp"
#include "app/research/sixdof/EffectAblation.hpp"
#include "app/research/sixdof/SixDofPlots.hpp"
#include "app/research/sixdof/SixDofRuns.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "engine/estimation/MotionModelFitter.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {

namespace {

struct Options {
  SimulationOptions simulation;
  std::string size = "640x480";
  bool baseline = true;
  bool fitQ = true;
  std::filesystem::path params;
  std::filesystem::path outDir = "experiment-6dof";
  std::filesystem::path cacheDir;  // reuse rendered sequences across runs when set
  std::string effects = "none";
  bool effectTable = false;
  bool knownReadout = false;            // --known-readout
  bool globalShutterModel = false;      // --global-shutter-model
  std::vector<std::string> effectRows;  // the table's rows; empty: all
};

// Clean, each effect alone, then all of them (the webcam preset).
void printEffectTable(const SimulationOptions& simulation, const TrackerParams& params,
                      const std::optional<ArMotionModel>& motion,
                      const std::filesystem::path& cacheDir, std::vector<std::string> lists) {
  if (lists.empty()) {
    lists = {"none"};
    for (const std::string& name : cameraEffectNames()) lists.push_back(name);
    lists.push_back("webcam");
  }
  const std::vector<EffectAblationRow> rows =
      runEffectAblation(simulation, lists, params, motion, cacheDir);
  std::printf(
      "\neffect ablation: %s, %d frames, %dx%d, seed %llu, regularised PoseTracker (A, B)\n",
      simulation.preset.c_str(), simulation.frames, simulation.size.width, simulation.size.height,
      static_cast<unsigned long long>(simulation.seed));
  std::printf("%-16s %8s %9s %9s %6s %10s %10s %10s  %s\n", "effects", "tracked", "cube_mean",
              "cube_p95", "lost", "sharp_lost", "d_mean", "render_ms", "first lost");
  const double cleanMean = rows.front().cubeMeanPx;
  for (const EffectAblationRow& r : rows)
    std::printf("%-16s %7.1f%% %9.3f %9.3f %6zu %10zu %+10.3f %10.1f  %s\n", r.effects.c_str(),
                r.trackedPercent(), r.cubeMeanPx, r.cubeP95Px, r.lostFrames.size(),
                r.sharpLostFrames.size(), r.cubeMeanPx - cleanMean, r.renderMsPerFrame,
                r.firstLostReason.c_str());
  std::printf(
      "d_mean: cube mean minus the clean run's; sharp_lost: lost frames whose cube vertices move "
      "< 1 px in the webcam exposure (%.0f ms)\n",
      cameraEffectsFor("blur", simulation.size).exposureMs);
}

void printRun(const TrackerRun& r, std::size_t frames) {
  const TrajectoryEvaluation& e = r.evaluation;
  for (std::size_t i = 0; i < std::min<std::size_t>(3, r.lostReasons.size()); ++i)
    std::fprintf(stderr, "%s lost %s\n", r.name.c_str(), r.lostReasons[i].c_str());
  const double cubeMean = e.cubeErrorPx ? e.cubeErrorPx->mean : NAN;
  const double cubeP95 = e.cubeErrorPx ? e.cubeErrorPx->p95 : NAN;
  std::printf(
      "%-22s %7.1f%% %9.3f %9.3f %9.3f %9.3f %9.4f %9.4f %9.2f %9.2f %9.2f\n", r.name.c_str(),
      100.0 * static_cast<double>(r.estimate.poses.size()) / static_cast<double>(frames), cubeMean,
      cubeP95, r.firstHundredMeanPx, r.lastHundredMeanPx, e.jitterPx.value_or(NAN),
      r.staticJitterPx, e.ateTranslationMm.mean, median(r.frameMs), median(r.frameCpuMs));
}

// Paper Sec. 5.3: Q is the covariance of frame-to-frame pose changes of a recorded trajectory;
// here the exact path of the same preset with another seed (nothing when fit is false).
std::optional<ArMotionModel> fittedMotion(const SimulationOptions& simulation, bool fit) {
  if (!fit) return std::nullopt;
  SimulationOptions other = simulation;
  other.seed += 1;
  other.effects = {};  // the path alone
  const SceneSimulator path(other);
  TumTrajectory recorded;
  for (int k = 0; k < other.frames; ++k)
    recorded.poses.push_back({k / other.fps, path.framePose(k)});
  ArMotionModel motion =
      MotionModelFitter::fit(MotionModelFitter::motionVectors(recorded), 0).model;
  const Vector6d sd = motion.processNoise().diagonal().cwiseSqrt();
  std::printf(
      "Q fitted to the %s path of seed %llu: SD per frame %.3g %.3g %.3g m, "
      "%.3g %.3g %.3g rad\n",
      other.preset.c_str(), static_cast<unsigned long long>(other.seed), sd[0], sd[1], sd[2], sd[3],
      sd[4], sd[5]);
  return motion;
}

CommandRegistration registerExperimentSixDofCommand(CLI::App& parent) {
  CLI::App* sub = parent.add_subcommand("experiment-6dof",
                                        "6-DOF tracking on a simulated sequence: accuracy, "
                                        "drift, jitter and speed vs a baseline");
  auto o = std::make_shared<Options>();
  o->simulation.frames = 1000;
  sub->add_option("--preset", o->simulation.preset, "Camera path")
      ->check(CLI::IsMember(simulationPresets()));
  sub->add_option("--frames", o->simulation.frames, "Frames")->check(CLI::Range(3, 100000));
  sub->add_option("--size", o->size, "Image size WxH")->check(imageSizeValidator());
  sub->add_option("--reference-baseline", o->simulation.referenceBaseline,
                  "Metres from reference A to B, sideways (default: the scene's 0.25)")
      ->check(CLI::Range(0.0, 1.0));
  sub->add_option("--references", o->simulation.references,
                  "Reference views (default: walkaround 6, others 2); with more than two, the "
                  "MultiReferenceTracker runs on all of them beside the two-reference PoseTracker "
                  "on A and B")
      ->check(CLI::Range(2, kMaxReferences));
  sub->add_option("--seed", o->simulation.seed, "Noise and shake seed");
  sub->add_option("--noise", o->simulation.noiseSigma, "Sensor noise SD (grey levels)")
      ->check(CLI::Range(0.0, 50.0));
  sub->add_flag("--blur", o->simulation.blur, "Motion blur");
  sub->add_option("--effects", o->effects,
                  "Webcam effects on the frames: none, webcam (all at typical levels) or a comma-"
                  "separated list of photos, blur, rolling-shutter, exposure, flicker, vignetting, "
                  "noise, defocus, compression")
      ->check(cameraEffectsValidator())
      ->capture_default_str();
  sub->add_flag("--effect-table", o->effectTable,
                "Instead of the comparison: the regularised tracker clean, with each effect "
                "alone and with all (webcam): tracked %, cube error mean and p95, lost frames");
  sub->add_option("--effect-rows", o->effectRows,
                  "With --effect-table: only these rows, comma-separated (none, an effect name, "
                  "webcam), in this order")
      ->delimiter(',')
      ->check(cameraEffectsValidator());
  sub->add_option("--fov", o->simulation.fovDeg, "Horizontal field of view, degrees")
      ->check(CLI::Range(10.0, 150.0));
  addDistortionOption(sub, o->simulation.distortion);
  sub->add_option("--params", o->params, "TrackerParams YAML")->check(CLI::ExistingFile);
  sub->add_flag(
      "--known-readout", o->knownReadout,
      "Give the tracker the simulated rolling shutter's readout "
      "(pose.rolling_shutter_readout = readout / frame interval; its online estimate off)");
  sub->add_flag("--global-shutter-model", o->globalShutterModel,
                "With a simulated rolling shutter, track with the global-shutter model (no "
                "readout correction) instead of estimating the readout online");
  sub->add_flag("!--no-baseline", o->baseline, "Skip the ORB + PnP + Kalman baseline");
  sub->add_flag("!--no-fit-q", o->fitQ,
                "Use Q from --params instead of fitting it (paper Sec. 5.3) to the ground truth "
                "of another run of the preset (seed + 1)");
  sub->add_option("--out", o->outDir, "Folder for the plots and trajectories");
  sub->add_option("--cache", o->cacheDir,
                  "Folder keeping rendered sequences (one subfolder per preset, size, frames, "
                  "seed, noise, ...): a repeated run loads the frames instead of rendering them");
  sub->footer(
      "Single thread (cv::setNumThreads(1)). Figures: tracked "
      "fraction, cube-vertex error (mean, "
      "p95, px), mean of the first and last 100 frames (drift), jitter "
      "(SD of the projected cube "
      "vertices over time: meaningful on --preset static), ATE (mm), "
      "median ms per frame (wall clock) and median thread CPU ms per frame (cpu_ms).");
  return {
      sub, [o] {
        o->simulation.size = *parseImageSize(o->size);
        o->simulation.effects = cameraEffectsFor(o->effects, o->simulation.size);
        cv::setNumThreads(1);
        const std::unique_ptr<render::GlContext> gl = render::createHeadlessContext();
        TrackerParams params = o->params.empty() ? TrackerParams{} : TrackerParams::load(o->params);
        if (o->knownReadout) {  // the camera's line delay is known: the tracker corrects for it
          params.pose.rollingShutterReadout =
              o->simulation.effects.readoutMs * o->simulation.fps / 1000.0;
          params.pose.estimateRollingShutter = false;
        } else if (o->simulation.effects.readoutMs > 0 && !o->globalShutterModel) {
          // A webcam's rolling shutter: as a user of such a camera would, the tracker estimates
          // the readout online (pose.estimate_rolling_shutter, off by default since issue 24: the
          // real clips measured were global shutter, or the estimate cost accuracy there).
          params.pose.estimateRollingShutter = true;
        }
        if (o->effectTable) {
          printEffectTable(o->simulation, params, fittedMotion(o->simulation, o->fitQ), o->cacheDir,
                           o->effectRows);
          return;
        }
        const SequenceMaps maps = o->simulation.referenceCount() > 2 ? SequenceMaps::AllReferences
                                                                     : SequenceMaps::TwoReferences;
        const SimulatedSequence s =
            o->cacheDir.empty()
                ? simulateSequence(o->simulation, {}, maps, params.relocalisation)
                : cachedSimulatedSequence(o->simulation, o->cacheDir, maps, params.relocalisation);
        const Preparation& prep = s.preparation;
        std::printf("map: %zu corners A, %zu corners B, %zu 3D points\n", prep.map.cornersA.size(),
                    prep.map.cornersB.size(), prep.map.matches.size());
        if (s.references)
          std::printf("N-reference map: %d references, %zu 3D points\n", s.references->size(),
                      s.references->points.size());
        const std::optional<ArMotionModel> motion = fittedMotion(o->simulation, o->fitQ);
        params.pose.estimator = PoseEstimatorKind::Standard;
        const TrackerRun standard = runPoseTracker(s, params, "standard (Eq. 12)", motion);
        params.pose.estimator = PoseEstimatorKind::Regularised;
        const TrackerRun regularised = runPoseTracker(s, params, "regularised (Eq. 13)", motion);
        std::optional<TrackerRun> multi;
        if (s.references)
          multi = runMultiReferenceTracker(
              s, params, std::to_string(s.references->size()) + " refs (regularised)", motion);
        std::optional<TrackerRun> baseline;
        if (o->baseline) baseline = runOrbBaseline(s);

        std::printf("\n%s, %d frames, %dx%d, fov %.0f, noise %.1f%s", o->simulation.preset.c_str(),
                    o->simulation.frames, o->simulation.size.width, o->simulation.size.height,
                    o->simulation.fovDeg, o->simulation.noiseSigma,
                    o->simulation.blur ? ", blur" : "");
        for (std::size_t i = 0; i < o->simulation.distortion.size(); ++i)
          std::printf("%s%g", i ? "," : ", distortion ", o->simulation.distortion[i]);
        std::printf(", effects %s\n", o->effects.c_str());
        std::printf("%-22s %8s %9s %9s %9s %9s %9s %9s %9s %9s %9s\n", "tracker", "tracked",
                    "cube_mean", "cube_p95", "first100", "last100", "jitter_px", "sd_px", "ATE_mm",
                    "ms_median", "cpu_ms");
        printRun(standard, s.frames.size());
        printRun(regularised, s.frames.size());
        if (multi) printRun(*multi, s.frames.size());
        if (baseline) printRun(*baseline, s.frames.size());
        if (multi) {
          std::printf("\nframes tracked per reference pair (%s):", multi->name.c_str());
          for (const auto& [pair, frames] : multi->pairUse)
            std::printf("  %s %d", pair.c_str(), frames);
          std::printf(
              "\nstandard / regularised rows: the paper's two-reference PoseTracker on references "
              "0 and 1\n");
        }
        std::printf("\nper-stage median ms (regularised):");
        for (const auto& [stage, ms] : regularised.stageMs)
          std::printf("  %s %.2f", stage.c_str(), median(ms));
        const auto jitter = [](const TrackerRun& r) {
          return std::max(1e-12, r.evaluation.jitterPx.value_or(NAN));
        };
        std::printf("\njitter ratio standard / regularised: %.2f\n",
                    jitter(standard) / jitter(regularised));
        if (baseline) {
          std::printf(
              "speed ratio baseline / regularised (median ms): %.2f wall, %.2f thread CPU\n",
              median(baseline->frameMs) / std::max(1e-9, median(regularised.frameMs)),
              median(baseline->frameCpuMs) / std::max(1e-9, median(regularised.frameCpuMs)));
          if (baseline->evaluation.cubeErrorPx && regularised.evaluation.cubeErrorPx)
            std::printf(
                "accuracy ratio baseline / regularised (mean cube error): "
                "%.2f\n",
                baseline->evaluation.cubeErrorPx->mean /
                    std::max(1e-12, regularised.evaluation.cubeErrorPx->mean));
          std::printf("jitter ratio baseline / regularised: %.2f\n",
                      jitter(*baseline) / jitter(regularised));
        }
        std::filesystem::create_directories(o->outDir);
        regularised.estimate.save(o->outDir / "trajectory_regularised.txt");
        standard.estimate.save(o->outDir / "trajectory_standard.txt");
        s.groundTruth.save(o->outDir / "groundtruth.txt");
        if (multi) multi->estimate.save(o->outDir / "trajectory_multi_reference.txt");
        std::vector<const TrackerRun*> runs{&standard, &regularised};
        if (multi) runs.push_back(&*multi);
        if (baseline) runs.push_back(&*baseline);
        writeCubeErrorPlot(s, runs, o->outDir / "cube_error.png");
        writeMotionComponentsPlot(s, standard, regularised, o->outDir / "motion_components.png");
        std::printf("wrote %s/{cube_error.png, motion_components.png, trajectories}\n",
                    o->outDir.string().c_str());
      }};
}

const CommandRegistrar registrar(60, registerExperimentSixDofCommand, CommandGroup::Research);

}  // namespace

}  // namespace reftrack::app
