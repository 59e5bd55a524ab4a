// `reftrack track`: runs a tracker over a frame source. Two modes: `homography` registers every
// frame to one reference image (paper Sec. 7.3; per-frame CSV of status, inlier ratio, H and
// milliseconds; labels drawn at their mapped positions in the recording) and `6dof` tracks the
// full pose against a prepared reference map (runSixDofTrack).
#include <cmath>
#include <cstdio>
#include <memory>
#include <opencv2/core/utility.hpp>

#include "app/commands/Commands.hpp"
#include "app/tracking/HomographyTrack.hpp"
#include "app/tracking/SixDofTrack.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

struct TrackArgs {
  std::string mode;  // empty: chosen from the other options
  std::filesystem::path reference, map, labels, camera, csv, record, trajectory, params, motion;
  std::string input;
  int frames = -1;
  std::vector<double> cubeAt;  // x,y,z or empty
  double cubeEdge = 0.0;       // 0: from the scene
  bool coldStarts = false;
  bool debugOverlay = false;
  int threads = -1;  // OpenCV's worker threads; -1: its default
  bool realtime = false;
};

// --mode when given; else homography with --reference, 6dof with --map, else the params' mode.
TrackingMode chooseMode(const TrackArgs& a) {
  if (!a.mode.empty()) return parseTrackingMode(a.mode);
  if (!a.reference.empty()) return TrackingMode::Homography;
  if (!a.map.empty()) return TrackingMode::SixDof;
  if (!a.params.empty()) return TrackerParams::load(a.params).mode;
  throw CLI::ValidationError("--mode", "give --reference (homography) or --map (6dof)");
}

// Options that only one mode uses; naming them in the other mode is a usage error.
void checkModeOptions(const TrackArgs& a, TrackingMode mode) {
  const auto forbid = [](bool given, const std::string& option, const std::string& modeName) {
    if (given) throw CLI::ValidationError(option, "is not used in " + modeName + " mode");
  };
  if (mode == TrackingMode::Homography) {
    if (a.reference.empty())
      throw CLI::ValidationError("--reference", "is required in homography mode");
    forbid(!a.map.empty(), "--map", "homography");
    forbid(!a.trajectory.empty(), "--trajectory", "homography");
    forbid(!a.motion.empty(), "--motion", "homography");
    forbid(!a.cubeAt.empty(), "--cube-at", "homography");
    forbid(a.cubeEdge > 0, "--cube-edge", "homography");
    forbid(a.realtime, "--realtime", "homography (it budgets the 6dof search after a loss)");
  } else {
    if (a.map.empty()) throw CLI::ValidationError("--map", "is required in 6dof mode");
    for (double c : a.cubeAt)
      if (!std::isfinite(c))
        throw CLI::ValidationError("--cube-at", "must be three finite numbers");
    forbid(!a.reference.empty(), "--reference", "6dof");
    forbid(!a.labels.empty(), "--labels", "6dof");
    forbid(!a.camera.empty(), "--camera", "6dof (the map holds the camera)");
  }
}

CommandRegistration registerTrackCommand(CLI::App& parent) {
  auto args = std::make_shared<TrackArgs>();
  CLI::App* sub =
      parent.add_subcommand("track", "Track a video, image folder, camera or simulation");
  sub->add_option("--mode", args->mode, "homography | 6dof (default: from the other options)")
      ->check(CLI::IsMember({"homography", "6dof"}));
  sub->add_option("--input", args->input,
                  "Video file, image folder or glob, camera:N, sim:PRESET, tum:DIR (TUM RGB-D "
                  "rgb.txt) or euroc:DIR (EuRoC cam0); dataset frames keep their timestamps")
      ->required();
  sub->add_option("--reference", args->reference, "Homography: the stored reference frame")
      ->check(CLI::ExistingFile);
  sub->add_option("--labels", args->labels, "Homography: labels YAML (text, x, y per label)")
      ->check(CLI::ExistingFile);
  sub->add_option("--camera", args->camera,
                  "Homography: camera.yml of the frames' camera (undistorts them; for a reference "
                  "of its size, taken from the same camera, also enables the rotation-only model "
                  "for frames that barely overlap it; a reference of another size is a picture "
                  "from another camera, used as it is; default for euroc: inputs: their "
                  "sensor.yaml)")
      ->check(CLI::ExistingFile);
  sub->add_option("--map", args->map, "6dof: folder written by `reftrack prepare`")
      ->check(CLI::ExistingDirectory);
  sub->add_option("--out-csv", args->csv, "Per-frame CSV");
  sub->add_option("--record", args->record, "MP4 of the registered overlay");
  sub->add_option("--trajectory", args->trajectory, "6dof: TUM trajectory (camera in world)");
  sub->add_option("--params", args->params, "TrackerParams YAML")->check(CLI::ExistingFile);
  sub->add_option("--motion", args->motion, "6dof: fitted motion model (fit-motion output)")
      ->check(CLI::ExistingFile);
  sub->add_option("--frames", args->frames, "Process at most N frames")
      ->check(CLI::Range(1, 100000000));
  sub->add_flag("--realtime", args->realtime,
                "6dof: budget the search after a loss in measured CPU time, as for a live camera "
                "(a file is otherwise searched the same way on every run, whatever the machine's "
                "load)");
  sub->add_flag("--cold-starts", args->coldStarts,
                "6dof: forget the past before every frame, so each frame is a cold start (the "
                "start near a reference, then relocalisation): measures starts, never needed to "
                "track");
  sub->add_option("--threads", args->threads,
                  "OpenCV's worker threads (default: OpenCV's choice; 1: everything on the "
                  "calling thread, so thread CPU times are the whole cost on one core)")
      ->check(CLI::Range(1, 1024));
  sub->add_option("--cube-at", args->cubeAt,
                  "6dof: x,y,z of the recorded cube's base centre (world, metres; upright in the "
                  "world frame; default: on the map's dominant plane near its middle)")
      ->delimiter(',')
      ->expected(3);
  sub->add_option("--cube-edge,--cube", args->cubeEdge,
                  "6dof: the recorded cube's edge (metres; default: scaled to the map's scene)")
      ->check(CLI::Range(1e-4, 100.0));
  sub->add_flag("--debug-overlay", args->debugOverlay,
                "Draw the tracker's corners, matches and status label in the recording too");
  sub->footer(
      "Homography CSV columns: index,timestamp,status,inlier_ratio,h11..h33,ms — status\n"
      "tracked|lost, H\n"
      "maps reference pixels to frame pixels (identity when lost), ms the tracker's time.\n"
      "Labels YAML: labels: [ { text: \"Tower\", x: 120.5, y: 80.0 }, ... ] in reference pixels.\n"
      "The reference and the frames may have different sizes (e.g. a phone photo as the\n"
      "reference, tracked in webcam video).");
  sub->parse_complete_callback([args] {
    try {
      checkModeOptions(*args, chooseMode(*args));
    } catch (const Error& e) {  // an unreadable --params file
      throw CLI::ValidationError("--params", e.what());
    }
  });
  return {sub, [args] {
            if (args->threads > 0) cv::setNumThreads(args->threads);
            if (chooseMode(*args) == TrackingMode::SixDof) {
              SixDofTrackOptions o;
              o.map = args->map;
              o.input = args->input;
              o.params = args->params;
              o.motion = args->motion;
              o.trajectory = args->trajectory;
              o.csv = args->csv;
              o.record = args->record;
              o.maxFrames = args->frames;
              if (!args->cubeAt.empty())
                o.cubeAt = Eigen::Vector3d(args->cubeAt[0], args->cubeAt[1], args->cubeAt[2]);
              if (args->cubeEdge > 0) o.cubeEdge = args->cubeEdge;
              o.debugOverlay = args->debugOverlay;
              o.coldStarts = args->coldStarts;
              o.realtime = args->realtime;
              runSixDofTrack(o);
              return;
            }
            HomographyTrackOptions o;
            o.reference = args->reference;
            o.input = args->input;
            o.labels = args->labels;
            o.camera = args->camera;
            o.params = args->params;
            o.csv = args->csv;
            o.record = args->record;
            o.maxFrames = args->frames;
            o.debugOverlay = args->debugOverlay;
            const HomographyTrackSummary s = runHomographyTrack(o);
            std::printf("homography: %d frames, %d tracked (%.1f%%), median %.2f ms per frame\n",
                        s.frames, s.tracked, 100.0 * s.tracked / s.frames, s.medianMs);
            if (!s.advice.empty()) std::printf("note: %s\n", s.advice.c_str());
            if (!o.csv.empty()) std::printf("per-frame CSV: %s\n", o.csv.string().c_str());
            if (!o.record.empty()) std::printf("recording: %s\n", o.record.string().c_str());
          }};
}

const CommandRegistrar registrar(40, registerTrackCommand);

}  // namespace

}  // namespace reftrack::app
