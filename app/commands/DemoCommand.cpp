// `reftrack demo`: the whole pipeline on the embedded scene with no download and no camera —
// simulate a handheld sequence with the marker in the two reference images, prepare the reference
// map from the marker, track every frame in full 6-DOF, draw the cube, record MP4 + trajectory,
// evaluate against the exact ground truth and print the summary; in a window when a display
// exists, else headless.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "app/commands/Commands.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "app/simulator/SimulationWriter.hpp"
#include "app/viewer/PoseFrameTracker.hpp"
#include "app/viewer/ViewerApp.hpp"
#include "engine/core/Error.hpp"
#include "engine/evaluation/TrajectoryEvaluator.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "engine/reference/ReferencePreparer.hpp"
#include "render/context/GlfwWindowContext.hpp"

namespace reftrack::app {

namespace {

struct DemoArgs {
  std::filesystem::path out = "demo-out";
  int frames = 300;
  bool headless = false;
};

// A hidden window when a display exists (shown once the viewer starts), else nullptr.
std::unique_ptr<render::GlfwWindowContext> tryOpenWindow() {
  if (!windowSystemAvailable()) return nullptr;
  render::WindowOptions options;
  options.title = "reftrack demo";
  options.visible = false;
  try {
    return std::make_unique<render::GlfwWindowContext>(options);
  } catch (const Error& e) {
    std::cerr << "reftrack demo: no window (" << e.what() << "); running headless\n";
    return nullptr;
  }
}

CommandRegistration registerDemoCommand(CLI::App& parent) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* sub = parent.add_subcommand(
      "demo", "Simulate, prepare, track in 6-DOF, record and evaluate (no download, no camera)");
  sub->footer(
      "Writes DIR/sequence/ (frames, camera.yml, groundtruth.txt, ...), DIR/demo.mp4 and\n"
      "DIR/demo_trajectory.txt. Opens a window when a display is available (close it to\n"
      "finish), otherwise runs headless.");
  sub->add_option("--out", args->out, "Output folder (created if missing)")->capture_default_str();
  sub->add_option("--frames", args->frames, "Frames to simulate (640x480)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_flag("--headless", args->headless, "Never open a window");

  return {sub, [args] {
            std::filesystem::create_directories(args->out);
            // One kind of GL context per process: the window's, or an off-screen one. The
            // simulator renders with it before the viewer starts.
            std::unique_ptr<render::GlContext> context;
            if (!args->headless) context = tryOpenWindow();
            const bool headless = !context;
            if (headless) context = render::createHeadlessContext();

            SimulationOptions sim;
            sim.preset = "handheld";
            sim.frames = args->frames;
            sim.size = {640, 480};
            const std::filesystem::path sequence = args->out / "sequence";
            {
              SceneSimulator simulator(sim);
              writeSimulation(simulator, sequence);
            }

            // Reference map from the marker seen in the two reference images (`reftrack prepare`).
            const PinholeCamera camera = PinholeCamera::load(sequence / "camera.yml");
            const Preparation prep = ReferencePreparer(camera).prepare(
                {cv::imread((sequence / "reference_a.png").string()), "reference_a.png"},
                {cv::imread((sequence / "reference_b.png").string()), "reference_b.png"},
                MarkerSpec::parse("DICT_6X6_250:23:0.2"));
            MultiReferenceMap::fromPair(prep.map).save(args->out / "scene");
            std::cout << "demo: reference map with " << prep.map.matches.size()
                      << " 3D points (marker reprojection RMS "
                      << prep.report.markerRmsA.value_or(NAN) << " / "
                      << prep.report.markerRmsB.value_or(NAN) << " px)\n";

            ViewerOptions view;
            view.input = (sequence / "frames").string();
            view.camera = sequence / "camera.yml";
            view.record = args->out / "demo.mp4";
            const ReferenceMap map = prep.map;
            view.makeTracker = [map](const PinholeCamera&, const TrackerParams& params) {
              return std::unique_ptr<FrameTracker>(std::make_unique<PoseFrameTracker>(map, params));
            };
            view.headless = headless;
            view.source.imageFps = sim.fps;
            const ViewerRunSummary s = runViewer(view, context.get());
            std::cout << "demo: " << s.framesProcessed << " frames (" << s.backend << ") in "
                      << s.seconds << " s, " << s.framesProcessed / std::max(s.seconds, 1e-9)
                      << " fr/s; source " << s.sourceFps << " fps\n"
                      << "  sequence    " << sequence.string() << "\n"
                      << "  video       " << s.recording.string() << "\n"
                      << "  trajectory  " << s.trajectory.string() << "\n";
            // Against the exact ground truth (`reftrack eval`).
            const TrajectoryEvaluation e =
                evaluateTrajectory(TumTrajectory::load(sequence / "groundtruth.txt"),
                                   TumTrajectory::load(s.trajectory), EvaluationParams{}, &camera);
            std::printf("\n%-34s %10s\n", "demo summary (6-DOF tracker)", "value");
            std::printf("%-34s %9.1f%%\n", "frames tracked", 100.0 * e.trackedFraction);
            std::printf("%-34s %10.3f\n", "ATE RMSE (mm)", e.ateTranslationMm.rmse);
            std::printf("%-34s %10.4f\n", "rotation error mean (deg)", e.ateRotationDeg.mean);
            if (e.cubeErrorPx) {
              std::printf("%-34s %10.3f\n", "cube vertex error mean (px)", e.cubeErrorPx->mean);
              std::printf("%-34s %10.3f\n", "cube vertex error p95 (px)", e.cubeErrorPx->p95);
            }
            if (e.jitterPx) std::printf("%-34s %10.4f\n", "jitter (px)", *e.jitterPx);
          }};
}

const CommandRegistrar registrar(5, registerDemoCommand);

}  // namespace

}  // namespace reftrack::app
