#pragma once
// LiveMapping: the viewer's side of building a reference map live (the Map panel). Captures the
// current frame with its pose - from the world-frame fiducial (marker or board) when it is in
// view, else from the live tracker's pose on the map being extended -, builds the map from the
// captures with `prepare`'s engine code (MultiReferencePreparer) and adds later captures with
// `extend`'s (MapExtender::add: matching + bundle adjustment, the world frame fixed), on a worker
// thread in the window and in line headless, and saves the map folder atomically. Reports into
// MapState; the viewer puts each new map to use for tracking (takeMapForTracking).
// Unprepared (no fiducial, `prepare --unprepared`'s engine code, UnpreparedInitializer): the
// first two captures have no pose; after the first, the motion since it is measured on recent
// frames (TwoViewMotion, on the worker thread in the window) and shown, and the second capture
// is refused while it cannot start a map (a pure rotation, too little parallax, a textureless
// view); Build map poses both from their matches with the baseline typed into the panel.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <future>
#include <memory>
#include <optional>

#include "app/sources/FrameSource.hpp"
#include "app/viewer/ViewerState.hpp"
#include "engine/mapping/MapExtender.hpp"
#include "engine/mapping/UnpreparedInitializer.hpp"
#include "engine/reference/TwoViewMotion.hpp"
#include "engine/reference/WorldFrameFiducial.hpp"
#include "render/gl/Texture2D.hpp"

namespace reftrack::app {

class LiveMapping {
 public:
  // `params.preparation` builds the map, `params.extension` and `bundleAdjustment` extend it,
  // `params.tracker` is the tracking it is extended with. `background`: build and add on a worker
  // thread so the video keeps playing. Throws reftrack::Error on bad params.
  LiveMapping(WorldFrameFiducial fiducial, PinholeCamera camera, MapExtenderParams params,
              bool background, MapState& state);
  // Unprepared: no fiducial; `unprepared` finds the first two captures' poses.
  LiveMapping(PinholeCamera camera, MapExtenderParams params, UnpreparedMapParams unprepared,
              bool background, MapState& state);
  ~LiveMapping();  // waits for running work
  LiveMapping(const LiveMapping&) = delete;
  LiveMapping& operator=(const LiveMapping&) = delete;

  // Once per loop iteration: carries out and clears the requests in `state` for `frame`.
  // `tracked`: the live tracker's pose of `frame` when it tracks the map built here.
  void update(const Frame& frame, const std::optional<RigidPose>& tracked, MapState& state);
  // Captures `frame` now; false (and why in state.message) when it cannot.
  bool capture(const Frame& frame, const std::optional<RigidPose>& tracked, MapState& state);
  // Builds the map from the captures now (waiting for running work first); false (and why in
  // state.message) when it cannot. For headless runs.
  bool buildNow(MapState& state);
  // Writes the map folder: into a new sibling folder first, then renamed into place, so a
  // failure (a full disk) leaves no half-written folder and an existing one untouched. False
  // (and why in state.message) on failure.
  bool save(const std::filesystem::path& folder, MapState& state);

  // The map built or extended last, once (the viewer then tracks on it).
  std::optional<MultiReferenceMap> takeMapForTracking();
  const std::optional<MultiReferenceMap>& map() const { return map_; }
  // The captures' world->camera poses, in capture order.
  std::vector<RigidPose> capturePoses() const;
  // The captures' thumbnails as GL textures (~96 px wide) into state; needs a current context.
  void uploadThumbnails(MapState& state);

 private:
  struct Captured {
    cv::Mat image;
    int frameIndex = -1;
    MeasuredPose pose;
    bool measured = true;  // from the fiducial (else from tracking)
    bool posed = true;     // false: unprepared, posed only once the map is built
  };
  struct Work {
    MultiReferenceMap map;
    std::string message;
    std::vector<std::pair<int, std::string>> notes;  // capture index -> why it was left out
    std::vector<int> added;                          // captures now in the map
    bool posesFromMap = false;  // unprepared build: capture added[k] is the map's view k
  };
  Work build(std::vector<Captured> captures) const;
  Work buildUnprepared(std::vector<Captured> captures, double baselineMetres) const;
  bool captureUnposed(const Frame& frame, MapState& state);
  // Unprepared, one capture and no map: measures the motion since the capture on `frame` (on the
  // worker thread in the window, at most one at a time) and shows the last result.
  void measureMotion(const Frame& frame, MapState& state);
  void showMotion(const TwoViewMotion& motion, int frameIndex, MapState& state) const;
  Work extend(MultiReferenceMap map, std::vector<std::pair<int, Captured>> pending) const;
  void start(std::function<Work()> work, const std::string& label, MapState& state);
  void collect(MapState& state);
  void report(MapState& state);
  void fail(MapState& state, const std::string& message) const;

  std::optional<WorldFrameFiducial> fiducial_;  // none: unprepared
  PinholeCamera camera_;
  MapExtenderParams params_;
  UnpreparedMapParams unprepared_;
  std::optional<TwoViewMotionEstimator> motion_;          // unprepared only
  std::shared_ptr<const TwoViewKeyframe> firstKeyframe_;  // of the first unposed capture
  std::future<TwoViewMotion> motionWork_;
  int motionWorkFrame_ = -1;
  bool background_;
  std::vector<Captured> captures_;
  std::vector<MapCapture> shown_;
  std::optional<MultiReferenceMap> map_;
  std::optional<MultiReferenceMap> forTracking_;
  std::future<Work> working_;
  std::shared_ptr<std::atomic<int>> done_ = std::make_shared<std::atomic<int>>(0);
  int total_ = 1;
  std::string unit_;  // what total_ counts
  std::chrono::steady_clock::time_point workStart_;
  std::vector<render::Texture2D> thumbnails_;
  bool thumbnailsStale_ = false;
};

}  // namespace reftrack::app
