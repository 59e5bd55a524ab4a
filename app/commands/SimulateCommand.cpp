// `reftrack simulate`: renders a ground-truth sequence of the synthetic desk scene (frames,
// camera.yml, reference views, TUM ground truth) for testing and benchmarking the tracker.
#include <iostream>
#include <memory>

#include "app/cli/CameraEffectsValidator.hpp"
#include "app/cli/DistortionOption.hpp"
#include "app/cli/ImageSizeValidator.hpp"
#include "app/commands/Commands.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "app/simulator/SimulationWriter.hpp"
#include "engine/core/Error.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {

namespace {

struct SimulateArgs {
  SimulationOptions options;
  std::string size = "640x480";
  std::filesystem::path out;
  std::string effects = "none";
};

CommandRegistration registerSimulateCommand(CLI::App& parent) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* sub = parent.add_subcommand(
      "simulate", "Render a ground-truth sequence of the synthetic desk scene");
  sub->footer(
      "Writes DIR/frames/000000.png..., camera.yml, reference_00.png... (one per reference,\n"
      "the first two also as reference_a.png, reference_b.png), references.txt (TUM, view i at\n"
      "timestamp i), scene.yml and groundtruth.txt (TUM: camera pose in the world, i.e. the\n"
      "inverse of world->camera). World frame = the ArUco marker's frame (DICT_6X6_250 id 23,\n"
      "0.2 m). The scene is fixed; --seed changes sensor noise and hand shake only.");
  SimulationOptions& o = args->options;
  sub->add_option("--preset", o.preset, "Camera path")
      ->check(CLI::IsMember(simulationPresets()))
      ->capture_default_str();
  sub->add_option("--frames", o.frames, "Number of frames")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  sub->add_option("--size", args->size, "Image size WIDTHxHEIGHT")
      ->check(imageSizeValidator())
      ->capture_default_str();
  sub->add_option("--out", args->out, "Output folder (created if missing)")->required();
  sub->add_option("--seed", o.seed, "Seed of sensor noise and hand shake")->capture_default_str();
  sub->add_option("--noise", o.noiseSigma, "Sensor noise SD in grey levels")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  sub->add_flag("--blur", o.blur, "Motion blur (mean of 5 sub-frame renders)");
  sub->add_option(
         "--effects", args->effects,
         "Webcam effects: none, webcam (all at typical levels) or a comma-separated list "
         "of photos, blur, rolling-shutter, exposure, flicker, vignetting, noise, defocus, "
         "compression")
      ->check(cameraEffectsValidator())
      ->capture_default_str();
  sub->add_option("--fov", o.fovDeg, "Horizontal field of view, degrees")
      ->check(CLI::Range(10.0, 150.0))
      ->capture_default_str();
  addDistortionOption(sub, o.distortion);
  sub->add_option("--reference-baseline", o.referenceBaseline,
                  "Metres from reference A to B, sideways (default: the scene's 0.25)")
      ->check(CLI::Range(0.0, 1.0));
  sub->add_option("--references", o.references,
                  "Reference views: A, B, then views on the walkaround arc (default: walkaround 6, "
                  "other presets 2)")
      ->check(CLI::Range(2, kMaxReferences));
  sub->add_option("--fps", o.fps, "Frame rate of the ground-truth timestamps")
      ->check(CLI::Range(0.001, 1000.0))
      ->capture_default_str();

  return {sub, [args] {
            SimulationOptions options = args->options;
            options.size = *parseImageSize(args->size);
            options.effects = cameraEffectsFor(args->effects, options.size);
            options.check();
            const auto context = render::createHeadlessContext();
            SceneSimulator sim(options);
            writeSimulation(sim, args->out);
            std::cout << "wrote " << options.frames << " frames (" << options.preset << ", "
                      << args->size << ") to " << args->out.string() << "\n";
          }};
}

const CommandRegistrar registrar(10, registerSimulateCommand);

}  // namespace

}  // namespace reftrack::app
