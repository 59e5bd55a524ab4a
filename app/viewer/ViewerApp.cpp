#include "app/viewer/ViewerApp.hpp"

// clang-format off
#include <glad/gl.h>  // before GLFW, which must not pull in a system GL header
#include <GLFW/glfw3.h>
// clang-format on
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/cli/Interruption.hpp"
#include "app/cli/ProgressBar.hpp"
#include "app/sources/FrameGrabber.hpp"
#include "app/sources/InputCamera.hpp"
#include "app/sources/LoopingFrameSource.hpp"
#include "app/sources/SimulatorSource.hpp"
#include "app/viewer/CalibrationPanel.hpp"
#include "app/viewer/LiveCalibration.hpp"
#include "app/viewer/LiveMapping.hpp"
#include "app/viewer/MapPanel.hpp"
#include "app/viewer/OverlayCompositor.hpp"
#include "app/viewer/OverlayPanel.hpp"
#include "app/viewer/PanelLayout.hpp"
#include "app/viewer/PoseFrameTracker.hpp"
#include "app/viewer/RecordPanel.hpp"
#include "app/viewer/ReferencesPanel.hpp"
#include "app/viewer/SourcePanel.hpp"
#include "app/viewer/StatsPanel.hpp"
#include "app/viewer/TrackingPanel.hpp"
#include "app/viewer/TrajectoryReplayTracker.hpp"
#include "app/viewer/VideoRecorder.hpp"
#include "app/viewer/ViewerState.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/TumTrajectory.hpp"
#include "engine/tracking/PredictedOverlayError.hpp"
#include "render/RenderTarget.hpp"
#include "render/context/GlfwWindowContext.hpp"
#include "render/gl/Texture2D.hpp"

namespace reftrack::app {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

void ViewerOptions::check() const {
  if (input.empty()) throw Error("--input is required");
  if (maxFrames == 0 || maxFrames < -1) throw Error("--frames must be positive");
  if (cubeSize && !(std::isfinite(*cubeSize) && *cubeSize > 0))
    throw Error("--cube-edge must be a positive size in metres");
  if (cubeAt && !cubeAt->allFinite()) throw Error("--cube-at must be three finite numbers");
  if (!model.empty() && !fs::is_regular_file(model))
    throw Error("model file '" + model.string() + "' does not exist");
  if (!camera.empty() && !fs::is_regular_file(camera))
    throw Error("camera file '" + camera.string() + "' does not exist");
  if (!poses.empty() && !fs::is_regular_file(poses))
    throw Error("trajectory file '" + poses.string() + "' does not exist");
  if (!groundTruth.empty() && !fs::is_regular_file(groundTruth))
    throw Error("ground-truth file '" + groundTruth.string() + "' does not exist");
  if (!screenshot.empty() && screenshot.extension() != ".png")
    throw Error("screenshot '" + screenshot.string() + "': the file name must end in .png");
  if (ui && !headless) throw Error("--ui applies to --headless runs (the window always has it)");
  if (!calibrateBoard.empty()) CalibrationBoard::parse(calibrateBoard);  // throws on a bad board
  if (calibrateEvery < 0) throw Error("--calibrate-every must not be negative");
  if (!calibrationOut.empty() && calibrateBoard.empty())
    throw Error("--calibration-out needs --calibrate BOARD");
  if (!calibrationOut.empty() && !headless)
    throw Error("--calibration-out applies to --headless runs (the window has a Save button)");
  if (loops < 1) throw Error("--loop must be at least 1");
  if (reportEvery < 0) throw Error("--report-every must not be negative");
  if (reportEvery > 0 && !headless) throw Error("--report-every applies to --headless runs");
  if (soakWarmup < 0) throw Error("--soak-warmup must not be negative");
  if (!mapMarker.empty() && !mapBoard.empty())
    throw Error("--marker and --board both fix the world frame: give one");
  if (!mapMarker.empty()) MarkerSpec::parse(mapMarker);  // throws on a bad marker
  if (!mapBoard.empty()) CalibrationBoard::parse(mapBoard);
  if (mapUnprepared && (!mapMarker.empty() || !mapBoard.empty()))
    throw Error("--unprepared builds a map without a marker or board: give no --marker / --board");
  if (mapBaseline != 0.0 && !mapUnprepared) throw Error("--baseline needs --unprepared");
  if (mapUnprepared && mapBaseline != 0.0 && !(std::isfinite(mapBaseline) && mapBaseline > 0.0))
    throw Error("--baseline must be a finite length in metres greater than 0");
  if (mapUnprepared && headless && !captureAt.empty() && mapBaseline == 0.0)
    throw Error(
        "--unprepared --capture-at needs --baseline M: how far the camera moved between "
        "the two captured frames (metres)");
  const bool mapping = this->mapping();
  if (!captureAt.empty() && !mapping)
    throw Error("--capture-at needs --marker, --board or --unprepared");
  if (!mapOut.empty() && !mapping) throw Error("--map-out needs --marker, --board or --unprepared");
  if ((!captureAt.empty() || !mapOut.empty()) && !headless)
    throw Error(
        "--capture-at and --map-out apply to --headless runs (the window has the Map panel)");
  if (!mapOut.empty() && captureAt.empty())
    throw Error("--map-out needs --capture-at I,J,... (the frames the map is built from)");
  for (int i : captureAt)
    if (i < 0) throw Error("--capture-at: frame indices must not be negative");
  if (mapping && !poses.empty())
    throw Error(
        "--poses replays a trajectory: it cannot be combined with --marker / --board / "
        "--unprepared");
  if (!trajectory.empty() && !headless)
    throw Error("--trajectory applies to --headless runs (the window records with Record)");
}

bool windowSystemAvailable() {
  for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY"}) {
    const char* value = std::getenv(name);
    if (value && *value) return true;
  }
  return false;
}

namespace {

// ---- Setup: source, camera, tracker -------------------------------------------------------

struct Session {
  std::unique_ptr<FrameGrabber> grabber;
  PinholeCamera camera;
  std::unique_ptr<FrameTracker> tracker;  // null: no poses (video only)
  // The frames' true poses (--gt, or a sim: input's own) beside a live tracker; null: none.
  std::unique_ptr<TrajectoryReplayTracker> truth;
  // Builds a live tracker for a camera (ViewerOptions::makeTracker); used again when a camera
  // calibrated in the viewer is put to use.
  std::function<std::unique_ptr<FrameTracker>(const PinholeCamera&, const TrackerParams&)>
      makeTracker;
  Frame first;
  std::vector<render::Texture2D> referenceThumbnails;  // the References panel's images
  bool trackerOnLiveMap = false;  // the tracker runs on the map built in the Map panel
  // The 6-DOF search after a loss is budgeted in measured CPU time (a live camera, or
  // --realtime), else in the modelled cost of its work (recorded input: the same every run).
  bool realTimeBudget = false;
};

// The References panel's thumbnails (GL textures, ~96 px wide) of the tracker's reference map;
// the panel is shown only when the tracker has one.
void showReferences(Session& s, ViewerState& state) {
  ReferencesState& r = state.references;
  r = ReferencesState{};
  s.referenceThumbnails.clear();
  if (!s.tracker) return;
  for (const ReferenceImage& image : s.tracker->referenceImages()) {
    r.names.push_back(image.name);
    if (image.image.empty()) {
      r.thumbnails.push_back(0);
      continue;
    }
    const double scale = 96.0 / image.image.cols;
    cv::Mat small;
    cv::resize(image.image, small, cv::Size(), scale, scale, cv::INTER_AREA);
    r.thumbnailSize = small.size();
    render::Texture2D texture;
    texture.upload(small, false);
    r.thumbnails.push_back(texture.id());
    s.referenceThumbnails.push_back(std::move(texture));
  }
  r.active = !r.names.empty();
}

Session openSession(const ViewerOptions& options, ViewerState& state) {
  Session s;
  state.settings = options.params.empty() ? ViewerSettings{} : ViewerSettings::load(options.params);
  if (options.mode) state.settings.tracker.mode = *options.mode;
  if (options.cubeSize) {
    state.settings.overlay.size = *options.cubeSize;
    state.settings.overlay.sizeFromScene = false;
  }
  if (options.cubeAt) {
    state.settings.overlay.offset = *options.cubeAt;
    state.settings.overlay.onScene = false;
  }
  if (options.debugOverlay) state.settings.overlay.setDebugLayers(true);
  if (!options.model.empty()) state.settings.overlay.modelPath = options.model.string();
  state.settings.check();
  if (!options.params.empty()) state.paramsPath = options.params.string();

  std::unique_ptr<FrameSource> source = openFrameSource(options.input, options.source);
  if (options.loops > 1)
    source = std::make_unique<LoopingFrameSource>(std::move(source), options.loops);
  const auto* sim = dynamic_cast<const SimulatorSource*>(source.get());
  std::string cameraName;
  // Calibrating without a camera file: K is guessed from the first frame's size below, and no
  // live tracker is built until the calibrated camera is put to use.
  const bool guessCamera = options.camera.empty() && !sim && !options.calibrateBoard.empty();
  s.makeTracker = options.makeTracker;
  const bool mapping = options.mapping();
  if (guessCamera) {
    cameraName = "the guessed camera";
  } else if (!options.camera.empty()) {
    s.camera = PinholeCamera::load(options.camera);
    cameraName = "camera file '" + options.camera.string() + "'";
  } else if (sim) {
    s.camera = sim->camera();
    cameraName = "the simulator's camera";
  } else if (std::optional<PinholeCamera> own = cameraFromInput(options.input)) {
    s.camera = *own;  // euroc: sensor.yaml
    cameraName = "the camera of input '" + options.input + "'";
  } else {
    throw Error("input '" + options.input +
                "' needs --camera camera.yml: the overlay needs the intrinsics K (only sim: and "
                "euroc: inputs bring their own camera)");
  }
  if (!options.poses.empty())
    s.tracker = std::make_unique<TrajectoryReplayTracker>(
        TrajectoryReplayTracker::load(options.poses, source->fps()));
  else if (options.makeTracker && !guessCamera)
    s.tracker = options.makeTracker(s.camera, state.settings.tracker);
  else if (sim && !mapping)
    s.tracker = std::make_unique<TrajectoryReplayTracker>(sim->groundTruth(), source->fps());
  s.realTimeBudget = options.realtime || source->isLive();
  if (s.tracker) {
    s.tracker->applyParams(state.settings.tracker);
    s.tracker->setRealTimeBudget(s.realTimeBudget);
  }
  // Ground truth beside a live tracker (a replayed trajectory is its own truth): the true overlay
  // error in the Stats panel.
  const bool liveTracker = (s.tracker && options.poses.empty() && options.makeTracker) || mapping;
  if (!options.groundTruth.empty() && liveTracker)
    s.truth = std::make_unique<TrajectoryReplayTracker>(
        TrajectoryReplayTracker::load(options.groundTruth, source->fps()));
  else if (sim && liveTracker)
    s.truth = std::make_unique<TrajectoryReplayTracker>(sim->groundTruth(), source->fps());
  state.stats.setGroundTruthLoaded(s.truth != nullptr);
  state.trackerName = s.tracker                            ? s.tracker->name()
                      : guessCamera && options.makeTracker ? "none until calibrated"
                      : mapping                            ? "none until the map is built"
                                                           : "none (no --poses)";

  state.source.description = source->description();
  state.source.frameCount = source->frameCount();
  state.source.fps = source->fps();
  state.source.seekable = source->seekable();
  state.source.live = source->isLive();
  s.grabber = std::make_unique<FrameGrabber>(std::move(source));

  std::optional<Frame> first = s.grabber->next();
  if (!first) throw Error("input '" + options.input + "' holds no frame");
  if (guessCamera) s.camera = PinholeCamera::fromFieldOfView(first->image.size(), 60.0);
  if (first->image.size() != s.camera.imageSize())
    throw Error(cameraName + " is for " + std::to_string(s.camera.imageSize().width) + "x" +
                std::to_string(s.camera.imageSize().height) + " frames but input '" +
                options.input + "' delivers " + std::to_string(first->image.cols) + "x" +
                std::to_string(first->image.rows) + " frames");
  s.first = std::move(*first);
  showReferences(s, state);
  return s;
}

// ---- Per-frame work shared by the window and headless loops ------------------------------

struct FrameLoop {
  Session& session;
  ViewerState& state;
  OverlayCompositor compositor;
  std::unique_ptr<VideoRecorder> recorder;
  std::unique_ptr<LiveCalibration> calibration;  // with --calibrate
  std::unique_ptr<LiveMapping> mapping;          // with --marker / --board / --unprepared
  // A map built unprepared: its world -> the truth's (session.truth), by its reference 0.
  std::optional<RigidPose> truthAnchor;
  std::optional<TumTrajectory> trajectory;  // the tracked poses (--trajectory)
  Frame current;
  TrackingResult result;
  Clock::time_point lastProcessed{};
  int processed = 0;
  int trackedFrames = 0;
  int predictedFrames = 0, trueFrames = 0;  // the overlay error's sums (ViewerRunSummary)
  double predictedSumPx = 0.0, trueSumPx = 0.0;

  FrameLoop(Session& s, ViewerState& st) : session(s), state(st) {}

  void applyTrackerParams() {
    if (!state.trackerParamsChanged) return;
    state.trackerParamsChanged = false;
    try {
      state.settings.tracker.check();
      if (session.tracker) session.tracker->applyParams(state.settings.tracker);
      state.paramsMessage.clear();
    } catch (const Error& e) {
      state.paramsMessage = e.what();
    }
  }

  std::string label() const {
    if (state.source.disconnected)
      return *state.source.disconnected + " - waiting for it to come back";
    return "frame " + std::to_string(current.index) + "  " + result.status + "  (" +
           state.trackerName + ")";
  }

  // A live camera that stopped delivering: shown on the video, and the recording is finished up
  // to the last frame (a new one can be started when the camera is back).
  void checkConnection() {
    std::optional<std::string> why = session.grabber->disconnected();
    if (why && !state.source.disconnected && recorder) {
      const int frames = recorder->framesWritten();
      const fs::path path = recorder->videoPath();
      try {
        stopRecording();
        state.record.message =
            *why + ": recording saved (" + std::to_string(frames) + " frames) to " + path.string();
      } catch (const Error& e) {
        state.record.message = e.what();
      }
    }
    state.source.disconnected = std::move(why);
  }

  // Tracks `frame` and makes it the current one.
  void process(Frame frame) {
    current = std::move(frame);
    if (current.image.size() != session.camera.imageSize())
      throw Error("frame " + std::to_string(current.index) + " is " +
                  std::to_string(current.image.cols) + "x" + std::to_string(current.image.rows) +
                  " but the camera is calibrated for " +
                  std::to_string(session.camera.imageSize().width) + "x" +
                  std::to_string(session.camera.imageSize().height));
    // The object stands on the tracked scene unless placed by hand (OverlaySettings::onScene).
    state.overlayEdit.scene =
        session.tracker ? session.tracker->scenePlacement() : std::optional<ScenePlacement>{};
    state.settings.overlay.applyScene(state.overlayEdit.scene);
    if (session.tracker) {
      session.tracker->setOverlayPoints(state.settings.overlay.cubeWorldVertices());
      result = session.tracker->process(current.image, current.index, current.timestamp);
    } else {
      result = TrackingResult{};
      result.status = "no poses";
    }
    const Clock::time_point now = Clock::now();
    FrameStats stats;
    stats.index = current.index;
    if (processed > 0)
      stats.loopMilliseconds =
          std::chrono::duration<double, std::milli>(now - lastProcessed).count();
    lastProcessed = now;
    stats.stages = result.stages;
    stats.matches = result.matches;
    stats.inliers = result.inliers;
    stats.status = result.status;
    stats.advice = result.advice;
    if (result.references) state.references.addFrame(*result.references);
    if (result.worldToCamera) stats.pose = result.worldToCamera->toVector6();
    if (trajectory && result.worldToCamera)
      trajectory->poses.push_back({current.timestamp, *result.worldToCamera});
    if (result.worldToCamera) ++trackedFrames;
    stats.predictedErrorPx = result.predictedErrorPx;
    if (session.truth && result.worldToCamera) {
      const TrackingResult truth =
          session.truth->process(current.image, current.index, current.timestamp);
      // A map of an unprepared scene has a world of its own: the truth is carried into it by
      // the first capture's view (truthAnchor), as `eval --anchor-map` does.
      if (truth.worldToCamera)
        stats.trueErrorPx =
            overlayErrorPx(session.camera,
                           truthAnchor ? *truth.worldToCamera * *truthAnchor : *truth.worldToCamera,
                           *result.worldToCamera, state.settings.overlay.cubeWorldVertices());
    }
    if (stats.predictedErrorPx) {
      predictedSumPx += *stats.predictedErrorPx;
      ++predictedFrames;
    }
    if (stats.trueErrorPx) {
      trueSumPx += *stats.trueErrorPx;
      ++trueFrames;
    }
    state.stats.add(std::move(stats));
    state.lastStatus = result.status;
    state.rollingShutterReadout = result.rollingShutterReadout;
    state.source.currentIndex = current.index;
    state.source.droppedFrames = session.grabber->droppedFrames();
    ++processed;
  }

  // Live calibration: carries out the Calibration panel's requests for the current frame and puts
  // a calibrated camera to use when asked.
  void updateCalibration() {
    if (!calibration) return;
    calibration->update(current, processed, state.calibration);
    if (std::optional<PinholeCamera> camera = calibration->takeCameraForTracking())
      useCamera(*camera);
  }

  // Live mapping: carries out the Map panel's requests for the current frame and tracks on each
  // map it builds or extends.
  void updateMapping() {
    if (!mapping) return;
    const std::optional<RigidPose> tracked =
        session.trackerOnLiveMap ? result.worldToCamera : std::nullopt;
    mapping->update(current, tracked, state.map);
    if (std::optional<MultiReferenceMap> map = mapping->takeMapForTracking())
      useMap(std::move(*map));
    mapping->uploadThumbnails(state.map);
  }

  void useMap(MultiReferenceMap map) {
    TrackerParams params = state.settings.tracker;
    params.mode = TrackingMode::SixDof;
    // Unprepared: the map's world -> the truth's, by the first capture (its reference 0):
    // X_truth = T0_truth^-1 T0_map X_map.
    truthAnchor.reset();
    if (state.map.unprepared && session.truth && !state.map.captures.empty()) {
      const MapCapture& first = state.map.captures.front();
      const TrackingResult at =
          session.truth->process(cv::Mat(), first.frameIndex, first.timestamp);
      if (at.worldToCamera) truthAnchor = at.worldToCamera->inverse() * map.views.front().T;
    }
    try {
      auto tracker = std::make_unique<PoseFrameTracker>(std::move(map), params);
      tracker->applyParams(params);
      tracker->setRealTimeBudget(session.realTimeBudget);
      session.tracker = std::move(tracker);
      session.trackerOnLiveMap = true;
      state.trackerName = session.tracker->name();
      state.map.tracking = true;
      showReferences(session, state);
    } catch (const std::exception& e) {
      state.map.message = std::string("cannot track on the map: ") + e.what();
      state.map.messageIsError = true;
    }
  }

  void useCamera(const PinholeCamera& camera) {
    CalibrationState& c = state.calibration;
    try {
      if (camera.imageSize() != session.camera.imageSize())
        throw Error("the calibrated camera is for another frame size");
      std::unique_ptr<FrameTracker> tracker;
      if (session.makeTracker) {
        tracker = session.makeTracker(camera, state.settings.tracker);
        tracker->applyParams(state.settings.tracker);
        tracker->setRealTimeBudget(session.realTimeBudget);
      }
      session.camera = camera;
      if (tracker) {
        session.tracker = std::move(tracker);
        state.trackerName = session.tracker->name();
        showReferences(session, state);
      }
      c.usedForTracking = true;
      c.message = tracker           ? "tracking with the calibrated camera"
                  : session.tracker ? "the overlay uses the calibrated camera"
                                    : "the overlay uses the calibrated camera (no live tracker: "
                                      "give --map or --reference)";
    } catch (const std::exception& e) {
      c.message = std::string("cannot use the camera: ") + e.what();
    }
  }

  // The next frame in order, honouring loop; false at the end.
  bool advance() {
    std::optional<Frame> frame = session.grabber->next();
    if (!frame && state.source.loop && state.source.seekable) {
      session.grabber->seek(0);
      frame = session.grabber->next();
    }
    if (!frame) {
      // A disconnected camera has not ended: frames come again once it is back.
      state.source.ended = !session.grabber->disconnected();
      return false;
    }
    state.source.ended = false;
    process(std::move(*frame));
    return true;
  }

  void startRecording(const fs::path& path, cv::Size size) {
    recorder = std::make_unique<VideoRecorder>(path, state.source.fps, size);
    state.record.recording = true;
    state.record.framesWritten = 0;
    state.record.message = "recording to " + path.string();
  }

  void record(const cv::Mat& bgr) {
    if (!recorder) return;
    recorder->write(bgr, current.timestamp, result.worldToCamera);
    state.record.framesWritten = recorder->framesWritten();
  }

  void summariseOverlayError(ViewerRunSummary& summary) const {
    summary.predictedErrorFrames = predictedFrames;
    summary.trueErrorFrames = trueFrames;
    if (predictedFrames > 0) summary.predictedErrorMeanPx = predictedSumPx / predictedFrames;
    if (trueFrames > 0) summary.trueErrorMeanPx = trueSumPx / trueFrames;
  }

  // Closes the recording; returns the paths written.
  std::pair<fs::path, fs::path> stopRecording() {
    if (!recorder) return {};
    std::unique_ptr<VideoRecorder> r = std::move(recorder);
    state.record.recording = false;
    r->close();
    state.record.message =
        "saved " + std::to_string(r->framesWritten()) + " frames to " + r->videoPath().string();
    return {r->videoPath(), r->trajectoryPath()};
  }
};

// ---- ImGui --------------------------------------------------------------------------------

// One ImGui context with the OpenGL 3 renderer, plus the GLFW platform backend in a window.
class ImGuiSession {
 public:
  explicit ImGuiSession(GLFWwindow* window) : window_(window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // fixed layout: no imgui.ini written or read
    ImGui::StyleColorsDark();
    if (window_ && !ImGui_ImplGlfw_InitForOpenGL(window_, true))
      throw Error("ImGui: the GLFW backend failed to initialise");
    if (!ImGui_ImplOpenGL3_Init("#version 330 core"))
      throw Error("ImGui: the OpenGL 3 backend failed to initialise");
  }
  ~ImGuiSession() {
    ImGui_ImplOpenGL3_Shutdown();
    if (window_) ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  ImGuiSession(const ImGuiSession&) = delete;
  ImGuiSession& operator=(const ImGuiSession&) = delete;

  // Starts a frame; headless, the display size and time step are set here (no platform backend).
  void newFrame(cv::Size headlessDisplay = {}, double headlessDeltaSeconds = 1.0 / 30) {
    ImGui_ImplOpenGL3_NewFrame();
    if (window_) {
      ImGui_ImplGlfw_NewFrame();
    } else {
      ImGuiIO& io = ImGui::GetIO();
      io.DisplaySize = ImVec2(static_cast<float>(headlessDisplay.width),
                              static_cast<float>(headlessDisplay.height));
      io.DeltaTime = static_cast<float>(headlessDeltaSeconds);
    }
    ImGui::NewFrame();
  }
  void render() {
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }

 private:
  GLFWwindow* window_;
};

void drawPanels(ViewerState& state, const PanelLayout& layout) {
  // The Map panel takes the Calibration panel's place (its lower half beside it).
  cv::Rect2f calibration = layout.calibration, map = layout.calibration;
  if (state.calibration.active && state.map.active) {
    calibration.height *= 0.5f;
    map.height -= calibration.height;
    map.y += calibration.height;
  }
  if (state.calibration.active) drawCalibrationPanel(state.calibration, calibration);
  if (state.map.active) drawMapPanel(state.map, map);
  drawSourcePanel(state.source, layout.source);
  drawTrackingPanel(state, layout.tracking);
  drawRecordPanel(state.record, layout.record);
  drawOverlayPanel(state.settings.overlay, state.overlayEdit, layout.overlay);
  drawStatsPanel(state.stats, layout.stats);
  if (state.references.active) drawReferencesPanel(state.references, layout.references);
}

// Opens the Calibration panel with `--calibrate BOARD`; auto-capture as asked (always headless).
void startCalibration(const ViewerOptions& options, FrameLoop& loop, cv::Size frameSize) {
  if (options.calibrateBoard.empty()) return;
  CalibrationState& c = loop.state.calibration;
  c.active = true;
  c.boardText = options.calibrateBoard;
  c.autoCapture = options.headless || options.calibrateEvery > 0;
  if (options.calibrateEvery > 0) c.autoCaptureEvery = options.calibrateEvery;
  if (options.headless) c.autoCaptureEvery = std::max(1, options.calibrateEvery);
  if (!options.calibrationOut.empty()) c.savePath = options.calibrationOut.string();
  loop.calibration = std::make_unique<LiveCalibration>(frameSize, !options.headless, c);
}

// Opens the Map panel with `--marker SPEC`, `--board SPEC` or `--unprepared`.
void startMapping(const ViewerOptions& options, FrameLoop& loop) {
  if (!options.mapping()) return;
  const PinholeCamera& camera = loop.session.camera;
  MapExtenderParams params;
  params.tracker = loop.state.settings.tracker;
  loop.state.map.active = true;
  if (!options.mapOut.empty()) loop.state.map.savePath = options.mapOut.string();
  if (options.mapUnprepared) {
    loop.state.map.baselineMetres = options.mapBaseline;
    loop.mapping = std::make_unique<LiveMapping>(camera, std::move(params), UnpreparedMapParams{},
                                                 !options.headless, loop.state.map);
    return;
  }
  WorldFrameFiducial fiducial =
      options.mapMarker.empty()
          ? WorldFrameFiducial::board(CalibrationBoard::parse(options.mapBoard), camera)
          : WorldFrameFiducial::marker(MarkerSpec::parse(options.mapMarker), camera);
  loop.mapping = std::make_unique<LiveMapping>(std::move(fiducial), camera, std::move(params),
                                               !options.headless, loop.state.map);
}

// Headless --capture-at: captures those frames, builds the map, tracks on it and rewinds the
// input to its first frame. Throws reftrack::Error with the panel's message when a step fails.
void captureAndBuild(const ViewerOptions& options, Session& session, FrameLoop& loop) {
  if (options.captureAt.empty()) return;
  MapState& m = loop.state.map;
  if (!loop.state.source.seekable)
    throw Error("--capture-at needs an input that can seek (a video file, an image folder, sim:)");
  const std::optional<int> count = loop.state.source.frameCount;
  for (int index : options.captureAt) {
    if (count && index >= *count)
      throw Error("--capture-at: frame " + std::to_string(index) + " is beyond the " +
                  std::to_string(*count) + " frames of '" + options.input + "'");
    session.grabber->seek(index);
    std::optional<Frame> frame = session.grabber->next();
    if (!frame)
      throw Error("--capture-at: input '" + options.input + "' has no frame " +
                  std::to_string(index));
    if (!loop.mapping->capture(*frame, std::nullopt, m)) throw Error(m.message);
    std::cout << "view: " << m.message << "\n";
  }
  if (!loop.mapping->buildNow(m)) throw Error(m.message);
  std::cout << "view: " << m.message << "\n";
  std::optional<MultiReferenceMap> map = loop.mapping->takeMapForTracking();
  if (map) loop.useMap(std::move(*map));
  if (!session.trackerOnLiveMap) throw Error(m.message);
  session.grabber->seek(0);
  std::optional<Frame> first = session.grabber->next();
  if (!first) throw Error("input '" + options.input + "' holds no frame");
  session.first = std::move(*first);
}

void writeScreenshot(const fs::path& file, const cv::Mat& bgr) {
  writeFileAtomically(file, [&](const fs::path& tmp) {
    // The temporary name keeps the extension so imwrite picks PNG.
    if (!cv::imwrite(tmp.string() + ".png", bgr))
      throw Error("screenshot '" + file.string() + "' cannot be written");
    fs::rename(tmp.string() + ".png", tmp);
  });
}

// The window's back buffer as BGR (row 0 at the top).
cv::Mat readWindowBgr(cv::Size size) {
  cv::Mat rgba(size, CV_8UC4);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, size.width, size.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data);
  cv::Mat bgr;
  cv::cvtColor(rgba, bgr, cv::COLOR_RGBA2BGR);
  cv::flip(bgr, bgr, 0);
  return bgr;
}

// ---- Headless: the same loop into an off-screen canvas --------------------------------------

ViewerRunSummary runHeadless(const ViewerOptions& options, render::GlContext& context) {
  const Clock::time_point start = Clock::now();
  ViewerState state;
  Session session = openSession(options, state);
  FrameLoop loop(session, state);
  const cv::Size frameSize = session.first.image.size();
  startCalibration(options, loop, frameSize);
  startMapping(options, loop);
  captureAndBuild(options, session, loop);
  if (!options.trajectory.empty()) loop.trajectory.emplace();
  const cv::Size canvasSize = options.ui ? options.canvasSize : frameSize;
  const std::optional<PanelLayout> layout =
      options.ui
          ? std::optional<PanelLayout>(panelLayout(
                canvasSize, state.calibration.active || state.map.active, state.references.active))
          : std::nullopt;
  const render::Viewport viewport = layout
                                        ? videoViewport(frameSize, layout->videoArea, canvasSize)
                                        : render::Viewport{0, 0, frameSize.width, frameSize.height};
  render::RenderTarget canvas(canvasSize);
  std::unique_ptr<ImGuiSession> imgui =
      options.ui ? std::make_unique<ImGuiSession>(nullptr) : nullptr;
  if (!options.record.empty()) loop.startRecording(options.record, canvasSize);

  std::optional<int> total = state.source.frameCount;
  if (options.maxFrames > 0)
    total = total ? std::min(*total, options.maxFrames) : options.maxFrames;
  std::unique_ptr<ProgressBar> progress =
      total ? std::make_unique<ProgressBar>("view", static_cast<std::size_t>(*total)) : nullptr;

  ViewerRunSummary summary;
  std::optional<SoakMonitor> soak;
  if (options.reportEvery > 0) soak.emplace(options.reportEvery, options.soakWarmup, &std::cout);
  cv::Mat lastCanvas;
  // Ctrl-C, or a frame that cannot be read or used mid-stream while recording, ends the loop
  // like the end of the input: the recording is finished up to the last frame drawn.
  const InterruptibleWork interruptible;
  std::string streamError;
  loop.process(std::move(session.first));
  for (;;) {
    loop.updateCalibration();
    loop.updateMapping();
    canvas.bind();
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    loop.compositor.draw(loop.current.image, session.camera, loop.result, state.settings.overlay,
                         viewport, loop.label());
    if (loop.calibration) loop.calibration->drawOverlay();
    if (imgui) {
      // ImGui lays windows out over two frames; the first frame is built twice so even a
      // one-frame run shows them settled.
      for (int pass = 0; pass < (loop.processed == 1 ? 2 : 1); ++pass) {
        imgui->newFrame(canvasSize, 1.0 / state.source.fps);
        drawPanels(state, *layout);
        if (pass == 0 && loop.processed == 1) ImGui::EndFrame();
      }
      canvas.bind();
      imgui->render();
    }
    lastCanvas = canvas.readColourBgr();
    loop.record(lastCanvas);
    if (progress) progress->advance();
    if (soak) soak->frameDone();
    if (options.maxFrames > 0 && loop.processed >= options.maxFrames) break;
    if (interruptRequested()) break;
    try {
      if (!loop.advance()) break;
    } catch (const Error& e) {
      if (!loop.recorder) throw;
      streamError = e.what();
      break;
    }
  }
  if (progress) progress->finish();
  if (const std::optional<std::string> why = session.grabber->disconnected())
    std::cerr << "view: " << *why << "; outputs finished up to the last frame\n";
  std::tie(summary.recording, summary.trajectory) = loop.stopRecording();
  if (!streamError.empty())
    throw Error(streamError + " (the recording '" + summary.recording.string() +
                "' holds every frame before it)");
  if (!options.screenshot.empty()) {
    writeScreenshot(options.screenshot, lastCanvas);
    summary.screenshot = options.screenshot;
  }
  if (loop.calibration) {
    CalibrationState& c = state.calibration;
    loop.calibration->calibrateNow(c);
    summary.calibrationCaptured = c.captured;
    summary.calibrationRejected = c.rejected;
    summary.calibration = c.result;
    summary.calibrationMessage = c.message;
    if (!options.calibrationOut.empty()) {
      if (!c.result) throw Error(c.message);
      CalibrationSession::save(*c.result, options.calibrationOut);
      summary.calibrationFile = options.calibrationOut;
    }
  }
  if (loop.mapping) {
    const MapState& m = state.map;
    const std::vector<RigidPose> poses = loop.mapping->capturePoses();
    for (std::size_t i = 0; i < m.captures.size() && i < poses.size(); ++i)
      summary.captures.push_back({m.captures[i].frameIndex, m.captures[i].timestamp, poses[i],
                                  m.captures[i].poseFrom, m.captures[i].fiducialRmsPx});
    summary.mapReferences = m.mapReferences;
    summary.mapPoints = m.mapPoints;
    summary.mapMessage = m.message;
    if (!options.mapOut.empty()) {
      if (!loop.mapping->save(options.mapOut, state.map)) throw Error(state.map.message);
      summary.mapFolder = options.mapOut;
    }
  }
  if (loop.trajectory) {
    loop.trajectory->save(options.trajectory);
    summary.trajectoryFile = options.trajectory;
  }
  summary.trackedFrames = loop.trackedFrames;
  summary.framesProcessed = loop.processed;
  loop.summariseOverlayError(summary);
  summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  summary.sourceFps = state.source.fps;
  summary.backend = context.backendName();
  if (soak) summary.soak = soak->summary();
  return summary;
}

// ---- Window: GLFW + ImGui, read top to bottom like ImGui's example_glfw_opengl3 -------------

ViewerRunSummary runWindow(const ViewerOptions& options, render::GlfwWindowContext& window) {
  const Clock::time_point start = Clock::now();
  ViewerState state;
  Session session = openSession(options, state);
  FrameLoop loop(session, state);
  ImGuiSession imgui(window.window());
  const cv::Size frameSize = session.first.image.size();
  startCalibration(options, loop, frameSize);
  startMapping(options, loop);
  if (!options.record.empty()) loop.startRecording(options.record, frameSize);
  if (!options.record.empty()) state.record.path = options.record.string();
  glfwShowWindow(window.window());

  ViewerRunSummary summary;
  loop.process(std::move(session.first));
  bool newFrame = true;  // the current frame still has to be recorded
  Clock::time_point due = Clock::now();
  bool finishing = false;
  const InterruptibleWork interruptible;  // Ctrl-C closes the window like its close button
  while (true) {
    window.pollEvents();
    if (window.shouldClose() || interruptRequested()) finishing = true;

    // Carry out the panels' requests.
    loop.applyTrackerParams();
    if (state.record.startRequested) {
      state.record.startRequested = false;
      try {
        loop.startRecording(state.record.path, frameSize);
      } catch (const Error& e) {
        state.record.message = e.what();
      }
    }
    if (state.record.stopRequested) {
      state.record.stopRequested = false;
      try {
        loop.stopRecording();
      } catch (const Error& e) {
        state.record.message = e.what();
      }
    }
    if (state.source.seekRequest) {
      const int target = *state.source.seekRequest;
      state.source.seekRequest.reset();
      session.grabber->seek(target);
      newFrame = loop.advance() || newFrame;
    }

    // Advance at the source rate times the speed (or one step when paused).
    const bool limitReached = options.maxFrames > 0 && loop.processed >= options.maxFrames;
    // With --frames the window closes by itself (also when the source ends first).
    if ((limitReached || (options.maxFrames > 0 && state.source.ended)) && !newFrame)
      finishing = true;
    loop.checkConnection();
    const bool wantFrame =
        !limitReached && !state.source.ended && !newFrame && session.grabber->frameReady() &&
        !state.source.disconnected &&
        ((state.source.playing && Clock::now() >= due) || state.source.stepRequested);
    if (wantFrame) {
      state.source.stepRequested = false;
      if (loop.advance()) {
        newFrame = true;
        due = Clock::now() +
              std::chrono::duration_cast<Clock::duration>(
                  std::chrono::duration<double>(1.0 / (state.source.fps * state.source.speed)));
      } else if (loop.recorder) {
        loop.stopRecording();  // the end of the source finishes the recording
      }
    }
    if (newFrame && loop.recorder) {
      try {
        loop.record(loop.compositor.composite(loop.current.image, session.camera, loop.result,
                                              state.settings.overlay, loop.label()));
      } catch (const Error& e) {
        if (state.settings.overlay.modelPath.empty()) throw;
        state.overlayEdit.message = e.what();  // a bad model path typed in the panel
        state.settings.overlay.modelPath.clear();
      }
    }
    newFrame = false;
    loop.updateCalibration();
    loop.updateMapping();

    // The UI.
    imgui.newFrame();
    int winW = 0, winH = 0;
    glfwGetWindowSize(window.window(), &winW, &winH);
    const cv::Size windowSize(std::max(winW, 1), std::max(winH, 1));
    const cv::Size fb = window.framebufferSize();
    std::optional<PanelLayout> layout;
    try {
      layout = panelLayout(windowSize, state.calibration.active || state.map.active,
                           state.references.active);
    } catch (const Error&) {
      layout.reset();  // window too small for the columns: video only
    }
    if (layout) drawPanels(state, *layout);

    // Draw: video + overlay letterboxed between the panel columns, then the UI on top.
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fb.width, fb.height);
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const double sx = static_cast<double>(fb.width) / windowSize.width;
    const double sy = static_cast<double>(fb.height) / windowSize.height;
    const cv::Rect area =
        layout ? cv::Rect(cvRound(layout->videoArea.x * sx), cvRound(layout->videoArea.y * sy),
                          cvRound(layout->videoArea.width * sx),
                          cvRound(layout->videoArea.height * sy))
               : cv::Rect(0, 0, fb.width, fb.height);
    try {
      loop.compositor.draw(loop.current.image, session.camera, loop.result, state.settings.overlay,
                           videoViewport(frameSize, area, fb), loop.label());
      if (loop.calibration) loop.calibration->drawOverlay();
    } catch (const Error& e) {
      if (state.settings.overlay.modelPath.empty()) throw;
      state.overlayEdit.message = e.what();
      state.settings.overlay.modelPath.clear();
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    imgui.render();

    if (finishing) {
      if (!options.screenshot.empty()) {
        writeScreenshot(options.screenshot, readWindowBgr(fb));
        summary.screenshot = options.screenshot;
      }
      break;
    }
    window.swapBuffers();
  }
  std::tie(summary.recording, summary.trajectory) = loop.stopRecording();
  if (summary.recording.empty() && !options.record.empty() && fs::exists(options.record)) {
    summary.recording = options.record;  // finished at the end of the source
    summary.trajectory = VideoRecorder::trajectoryPathFor(options.record);
  }
  summary.framesProcessed = loop.processed;
  loop.summariseOverlayError(summary);
  summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  summary.sourceFps = state.source.fps;
  summary.backend = window.backendName();
  return summary;
}

}  // namespace

ViewerRunSummary runViewer(const ViewerOptions& options, render::GlContext* context) {
  options.check();
  // One malloc arena for the threads started from here (frame grabber, encoders): with glibc's
  // default per-thread arenas, resident memory crept +3.0 MiB over a 20,000-frame soak
  // (scripts/soak.sh) although heaptrack found nothing leaked by our code; with one arena
  // (MALLOC_ARENA_MAX=1) the same soak grew +1.2 MiB, CPU time per frame unchanged (ratio 1.047).
  mallopt(M_ARENA_MAX, 1);
  if (options.headless) {
    std::unique_ptr<render::GlContext> owned;
    if (!context) {
      owned = render::createHeadlessContext();
      context = owned.get();
    }
    context->makeCurrent();
    return runHeadless(options, *context);
  }
  std::unique_ptr<render::GlfwWindowContext> owned;
  auto* window = dynamic_cast<render::GlfwWindowContext*>(context);
  if (context && !window) throw Error("the viewer window needs a GLFW window context");
  if (!window) {
    render::WindowOptions windowOptions;
    windowOptions.title = "reftrack view: " + options.input;
    windowOptions.size = options.canvasSize;
    windowOptions.visible = false;  // shown once the source is open
    owned = std::make_unique<render::GlfwWindowContext>(windowOptions);
    window = owned.get();
  }
  window->makeCurrent();
  return runWindow(options, *window);
}

}  // namespace reftrack::app
