// `reftrack view`: the AR viewer — frames from a video, an image folder or glob, a live camera or
// the simulator, the virtual object drawn at the tracked pose, ImGui panels, recording; in a
// window, or headless (OSMesa/EGL) for screenshots and recordings.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "app/cli/ImageSizeValidator.hpp"
#include "app/cli/ParsingValidator.hpp"
#include "app/commands/Commands.hpp"
#include "app/simulator/SimulationOptions.hpp"
#include "app/viewer/HomographyFrameTracker.hpp"
#include "app/viewer/ModeSwitchingTracker.hpp"
#include "app/viewer/PoseFrameTracker.hpp"
#include "app/viewer/ViewerApp.hpp"
#include "engine/calibration/CalibrationBoard.hpp"
#include "engine/core/Error.hpp"
#include "engine/reference/MarkerSpec.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack::app {

namespace {

struct ViewArgs {
  ViewerOptions options;
  double cubeSize = 0.0;
  std::vector<double> cubeAt;  // x,y,z or empty
  std::string simSize = "640x480";
  std::filesystem::path map, reference, labels;
};

std::string describeCamera(const PinholeCamera& c) {
  std::string text = "fx " + std::to_string(c.fx()) + " fy " + std::to_string(c.fy()) + " cx " +
                     std::to_string(c.cx()) + " cy " + std::to_string(c.cy()) + ", distortion";
  if (!c.hasDistortion()) return text + " none";
  for (double d : c.distortion()) text += " " + std::to_string(d);
  return text;
}

// Same size, K equal to 1e-7 (relative) and the same distortion (missing coefficients count as
// zero).
bool sameCalibration(const PinholeCamera& a, const PinholeCamera& b) {
  if (a.imageSize() != b.imageSize() || !a.K().isApprox(b.K(), 1e-7)) return false;
  const std::size_t n = std::max(a.distortion().size(), b.distortion().size());
  for (std::size_t i = 0; i < n; ++i) {
    const double da = i < a.distortion().size() ? a.distortion()[i] : 0.0;
    const double db = i < b.distortion().size() ? b.distortion()[i] : 0.0;
    if (std::abs(da - db) > 1e-9) return false;
  }
  return true;
}

// The map, when it was prepared with the viewer's camera: the tracker undistorts with the map's
// camera and the overlay distorts with the viewer's, so they must be the same lens.
MultiReferenceMap loadMapFor(const std::filesystem::path& folder, const PinholeCamera& camera) {
  MultiReferenceMap map = MultiReferenceMap::load(folder);
  if (!sameCalibration(map.camera, camera))
    throw Error("the camera (" + describeCamera(camera) + ") differs from the one '" +
                folder.string() + "' was prepared with (" + describeCamera(map.camera) +
                "): prepare the map with this camera.yml");
  return map;
}

// Live mapping (headless --capture-at): the captured references, each with its camera in the
// world as in a TUM line (`capture I frame F t T centre X Y Z quat QX QY QZ QW`), the map and the
// tracked fraction.
void printMapSummary(const ViewerRunSummary& s) {
  if (!s.captures.empty() || s.mapReferences > 0) {
    for (std::size_t i = 0; i < s.captures.size(); ++i) {
      const ViewerRunSummary::Capture& c = s.captures[i];
      const RigidPose cw = c.worldToCamera.inverse();
      const Eigen::Quaterniond q(cw.rotation());
      const Eigen::Vector3d t = cw.translation();
      std::printf(
          "capture %zu frame %d t %.6f centre %.6f %.6f %.6f quat %.9f %.9f %.9f %.9f (pose from "
          "the %s",
          i, c.frameIndex, c.timestamp, t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w(),
          c.poseFrom.c_str());
      if (c.fiducialRmsPx >= 0) std::printf(", corner RMS %.3f px", c.fiducialRmsPx);
      std::printf(")\n");
    }
    std::printf("map: %d references, %zu points\n", s.mapReferences, s.mapPoints);
    if (!s.mapFolder.empty()) std::printf("wrote map %s\n", s.mapFolder.string().c_str());
  }
  if (!s.trajectoryFile.empty())
    std::printf("tracked %d of %d frames (%.1f%%); wrote trajectory %s\n", s.trackedFrames,
                s.framesProcessed, 100.0 * s.trackedFrames / std::max(1, s.framesProcessed),
                s.trajectoryFile.string().c_str());
}

CommandRegistration registerViewCommand(CLI::App& parent) {
  auto args = std::make_shared<ViewArgs>();
  ViewerOptions& o = args->options;
  CLI::App* sub = parent.add_subcommand(
      "view", "Show (or record) the virtual object over video at the tracked pose");
  sub->footer(
      "SRC: a video file, a folder of images, a glob (\"frames/*.png\"), camera:N (live camera)\n"
      "or sim:PRESET (the simulator on the fly: handheld, orbit, rotate, static, forward),\n"
      "tum:DIR (TUM RGB-D rgb.txt) or euroc:DIR (EuRoC cam0; its sensor.yaml is the camera\n"
      "when --camera is not given); dataset frames keep their timestamps.\n"
      "Poses come from the 6-DOF tracker (--map), the homography tracker (--reference), or a\n"
      "replayed trajectory (--poses, TUM camera in world); sim: inputs without them replay\n"
      "their ground truth. With a live tracker the Stats panel plots the overlay error the\n"
      "pose covariance predicts, and beside it the true one when the frames' poses are known\n"
      "(--gt TUM file; sim: inputs bring their own).\n"
      "Recording writes OUT.mp4 (one frame per processed frame, at\n"
      "the source frame rate) and OUT_trajectory.txt (TUM) beside it.\n"
      "--calibrate BOARD opens the Calibration panel (capture views, coverage, calibrate, save\n"
      "camera.yml, use it for tracking); --camera is then optional. Headless, every frame is\n"
      "examined, views are captured automatically and the camera is calibrated at the end.\n"
      "--marker DICT:ID:SIZE or --board BOARD opens the Map panel: capture references (posed by\n"
      "the marker / board, or by tracking once a map exists), Build map (prepare's pipeline),\n"
      "Add to map (extend's), Save map. Headless: --capture-at I,J,... captures those frames,\n"
      "builds the map, tracks the whole input on it from its first frame, and writes --map-out\n"
      "and --trajectory.\n"
      "--unprepared opens the Map panel without a marker or board: capture two views from two\n"
      "places (the panel shows the parallax it sees and refuses a pure rotation, too little\n"
      "parallax or a textureless view), type how far the camera moved (Baseline, metres), Build\n"
      "map: the poses come from the views' own matches, the world lies on the scene's dominant\n"
      "plane. Headless: --unprepared --baseline M --capture-at I,J.");
  sub->add_option("--input", o.input, "Frame source SRC")->required();
  sub->add_option("--camera", o.camera, "camera.yml (required unless SRC is sim: or euroc:)")
      ->check(CLI::ExistingFile);
  sub->add_option("--poses", o.poses, "TUM trajectory to replay as the poses")
      ->check(CLI::ExistingFile);
  sub->add_option("--gt", o.groundTruth,
                  "TUM ground truth of the frames: with --map, the Stats panel plots the "
                  "overlay's true error beside the predicted one")
      ->check(CLI::ExistingFile);
  sub->add_option("--params", o.params, "Parameter YAML (TrackerParams + overlay section)")
      ->check(CLI::ExistingFile);
  sub->add_option("--cube-edge,--overlay-cube", args->cubeSize,
                  "Cube edge in metres (default: scaled to the map's scene, else 0.1 or the "
                  "--params overlay size)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--cube-at", args->cubeAt,
                  "x,y,z of the cube's base centre (world, metres; upright in the world frame; "
                  "default: on the map's dominant plane near its middle, else the --params "
                  "overlay offset)")
      ->delimiter(',')
      ->expected(3);
  sub->add_flag("--debug-overlay", o.debugOverlay,
                "Draw the tracker's corners, matches and status label over the video (and in "
                "recordings and screenshots) from the start");
  sub->add_option("--model", o.model, "OBJ model drawn instead of the cube")
      ->check(CLI::ExistingFile);
  sub->add_flag("--headless", o.headless, "No window: render off-screen (OSMesa/EGL)");
  sub->add_option("--frames", o.maxFrames, "Stop after N frames")->check(CLI::Range(1, 100000000));
  sub->add_option("--record", o.record, "Record the composited output to this .mp4");
  sub->add_option("--screenshot", o.screenshot, "Save the last drawn image to this .png");
  sub->add_flag("--ui", o.ui, "Headless: draw the ImGui panels too");
  sub->add_option("--fps", o.source.imageFps, "Frame rate of image folders and sim: inputs")
      ->check(CLI::Range(0.001, 1000.0))
      ->capture_default_str();
  sub->add_option("--map", args->map, "Reference map folder (`reftrack prepare`): 6-DOF tracking")
      ->check(CLI::ExistingDirectory);
  sub->add_option("--reference", args->reference, "Reference frame: homography tracking")
      ->check(CLI::ExistingFile);
  sub->add_option("--labels", args->labels, "Homography mode: labels YAML of the reference frame")
      ->check(CLI::ExistingFile);
  sub->add_option("--sim-frames", o.source.simFrames, "Length of a sim: sequence")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  sub->add_option("--sim-size", args->simSize, "Image size of a sim: sequence")
      ->check(imageSizeValidator())
      ->capture_default_str();

  sub->add_flag("--realtime", o.realtime,
                "Budget the search after a loss in measured CPU time, as for a live camera (a "
                "file is otherwise searched the same way on every run, whatever the machine's "
                "load)");
  sub->add_option("--loop", o.loops, "Play a video file or image folder N times in a row")
      ->check(CLI::Range(1, 1000000));
  sub->add_option("--report-every", o.reportEvery,
                  "Headless soak report: resident memory and frame rate every N frames")
      ->check(CLI::Range(1, 100000000));
  sub->add_option("--soak-warmup", o.soakWarmup,
                  "Frames before the soak's memory and rate baseline (with --report-every)")
      ->check(CLI::Range(0, 100000000))
      ->capture_default_str();
  sub->add_option("--calibrate", o.calibrateBoard,
                  "Live calibration with this board: chessboard:COLSxROWS:SQUARE_M (inner "
                  "corners) or charuco:DICT:SQXxSQY:SQUARE_M:MARKER_M")
      ->check(parsingValidator<CalibrationBoard>("BOARD"));
  sub->add_option("--calibrate-every", o.calibrateEvery,
                  "Auto-capture a view every N frames while the board is found (headless: "
                  "default 1)")
      ->check(CLI::Range(1, 100000));
  sub->add_option("--calibration-out", o.calibrationOut,
                  "Headless --calibrate: write the calibrated camera.yml here");
  CLI::Option* marker =
      sub->add_option("--marker", o.mapMarker,
                      "Map panel: the world frame from this ArUco marker DICT:ID:SIDE_M, e.g. "
                      "DICT_6X6_250:23:0.2")
          ->check(parsingValidator<MarkerSpec>("MARKER"));
  CLI::Option* board =
      sub->add_option("--board", o.mapBoard,
                      "Map panel: the world frame from this calibration board in view, "
                      "chessboard:COLSxROWS:SQUARE_M (inner corners) or "
                      "charuco:DICT:SQXxSQY:SQUARE_M:MARKER_M")
          ->check(parsingValidator<CalibrationBoard>("BOARD"));
  marker->excludes(board);
  CLI::Option* unprepared = sub->add_flag(
      "--unprepared", o.mapUnprepared,
      "Map panel without a marker or board: two captures posed by their own matches, the scale "
      "from the baseline");
  CLI::Option* baseline =
      sub->add_option("--baseline", o.mapBaseline,
                      "With --unprepared: how far the camera moved between the first two "
                      "captures (metres; the Map panel's Baseline field)")
          ->check(CLI::Validator(
              [](std::string& v) -> std::string {
                double x = 0.0;
                if (!CLI::detail::lexical_cast(v, x) || !std::isfinite(x) || !(x > 0.0))
                  return "must be a finite length in metres greater than 0, got '" + v + "'";
                return "";
              },
              "METRES"));
  unprepared->excludes(marker)->excludes(board);
  baseline->needs(unprepared);
  sub->add_option("--capture-at", o.captureAt,
                  "Headless, with --marker/--board/--unprepared: capture these frames as "
                  "references, build the map and track the input on it")
      ->delimiter(',')
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--map-out", o.mapOut, "Headless --capture-at: write the map folder here");
  sub->add_option("--trajectory", o.trajectory,
                  "Headless: write the tracked poses here (TUM, camera in world)");

  return {sub, [args, sub] {
            ViewerOptions options = args->options;
            if (sub->count("--cube-edge") > 0) options.cubeSize = args->cubeSize;
            if (!args->cubeAt.empty())
              options.cubeAt = Eigen::Vector3d(args->cubeAt[0], args->cubeAt[1], args->cubeAt[2]);
            options.source.simSize = *parseImageSize(args->simSize);
            if (args->map.empty() != args->reference.empty())
              options.mode = args->map.empty() ? TrackingMode::Homography : TrackingMode::SixDof;
            if (!args->map.empty() || !args->reference.empty()) {
              // Live tracking: 6-DOF against the map and/or homography against the reference;
              // the Tracking panel's mode switch selects between those given.
              const std::filesystem::path map = args->map, reference = args->reference,
                                          labels = args->labels;
              options.makeTracker = [map, reference, labels](const PinholeCamera& camera,
                                                             const TrackerParams& params) {
                std::unique_ptr<FrameTracker> sixDof, homography;
                if (!map.empty())
                  sixDof = std::make_unique<PoseFrameTracker>(loadMapFor(map, camera), params);
                if (!reference.empty()) {
                  const cv::Mat ref = cv::imread(reference.string(), cv::IMREAD_COLOR);
                  if (ref.empty())
                    throw Error("reference frame '" + reference.string() + "' cannot be read");
                  homography = std::make_unique<HomographyFrameTracker>(
                      ref, params, camera,
                      labels.empty() ? AnnotationSet{} : AnnotationSet::load(labels));
                }
                const TrackingMode initial = map.empty()         ? TrackingMode::Homography
                                             : reference.empty() ? TrackingMode::SixDof
                                                                 : params.mode;
                return std::unique_ptr<FrameTracker>(std::make_unique<ModeSwitchingTracker>(
                    std::move(sixDof), std::move(homography), initial));
              };
            }
            const ViewerRunSummary s = runViewer(options);
            std::cout << "processed " << s.framesProcessed << " frames in " << s.seconds << " s ("
                      << s.backend << ")\n";
            if (!s.recording.empty())
              std::cout << "recorded " << s.recording.string() << " and " << s.trajectory.string()
                        << "\n";
            if (!s.screenshot.empty()) std::cout << "screenshot " << s.screenshot.string() << "\n";
            if (s.predictedErrorFrames > 0)
              std::printf("overlay error of the cube: predicted mean %.3f px over %d frames\n",
                          s.predictedErrorMeanPx, s.predictedErrorFrames);
            if (s.trueErrorFrames > 0)
              std::printf(
                  "overlay error of the cube: true mean %.3f px over %d frames (ground "
                  "truth)\n",
                  s.trueErrorMeanPx, s.trueErrorFrames);
            if (s.soak) printSoakSummary(std::cout, *s.soak);
            printMapSummary(s);
            if (!options.calibrateBoard.empty() && options.headless) {
              std::printf("calibration: %d views captured, %d rejected\n", s.calibrationCaptured,
                          s.calibrationRejected);
              if (s.calibration) {
                const CalibrationResult& r = *s.calibration;
                std::printf("RMS reprojection error: %.4f px\n", r.rmsPx);
                std::printf("fx %.3f  fy %.3f  cx %.3f  cy %.3f\n", r.camera.fx(), r.camera.fy(),
                            r.camera.cx(), r.camera.cy());
                for (const CalibrationViewError& v : r.views)
                  std::printf("  %-10s %4d corners  %.4f px\n", v.label.c_str(), v.corners,
                              v.rmsPx);
              } else {
                std::printf("%s\n", s.calibrationMessage.c_str());
              }
              if (!s.calibrationFile.empty())
                std::printf("wrote %s\n", s.calibrationFile.string().c_str());
            }
          }};
}

const CommandRegistrar registrar(50, registerViewCommand);

}  // namespace

}  // namespace reftrack::app
