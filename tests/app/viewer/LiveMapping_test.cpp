// LiveMapping on the simulator (handheld, marker DICT_6X6_250:23:0.2): captures posed by the
// marker, the same-place and no-marker refusals, Build map with too few captures and with two
// (the map's references at the true poses), Add to map with the marker covered (posed by
// tracking), saving atomically (a failed save leaves no folder) and the worker-thread build.
#include "app/viewer/LiveMapping.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <chrono>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "TestPaths.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "app/viewer/PoseFrameTracker.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

class LiveMappingTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context_ = render::createHeadlessContext().release();
    SimulationOptions o;
    o.preset = "handheld";
    o.frames = 120;
    sim_ = new SceneSimulator(o);
  }
  static void TearDownTestSuite() {
    delete sim_;
    delete context_;
  }
  static Frame frame(int k) { return Frame{sim_->renderFrame(k), k, k / 30.0}; }
  static LiveMapping mapping(MapState& state, bool background = false) {
    return LiveMapping(WorldFrameFiducial::marker(sim_->marker(), sim_->camera()), sim_->camera(),
                       MapExtenderParams{}, background, state);
  }
  static render::GlContext* context_;
  static SceneSimulator* sim_;
};
render::GlContext* LiveMappingTest::context_ = nullptr;
SceneSimulator* LiveMappingTest::sim_ = nullptr;

TEST_F(LiveMappingTest, RefusesCapturesWithoutTheMarkerOrFromTheSamePlace) {
  MapState state;
  LiveMapping m(WorldFrameFiducial::marker(sim_->marker(), sim_->camera()), sim_->camera(),
                MapExtenderParams{}, false, state);
  EXPECT_EQ(state.fiducial, "marker DICT_6X6_250:23:0.2");
  const Frame blank{cv::Mat(sim_->camera().imageSize(), CV_8UC3, cv::Scalar(90, 90, 90)), 5, 0.0};
  EXPECT_FALSE(m.capture(blank, std::nullopt, state));
  EXPECT_TRUE(state.messageIsError);
  EXPECT_NE(state.message.find("cannot capture frame 5: no marker in view and not tracking"),
            std::string::npos)
      << state.message;
  ASSERT_TRUE(m.capture(frame(0), std::nullopt, state)) << state.message;
  // Frame 1 is ~1 mm from frame 0 along the handheld path: below preparation.min_baseline_m.
  EXPECT_FALSE(m.capture(frame(1), std::nullopt, state));
  EXPECT_NE(state.message.find("mm from reference 0 (frame 0)"), std::string::npos)
      << state.message;
  EXPECT_EQ(state.captures.size(), 1u);
  // Build with one reference: a message, no map.
  state.buildRequested = true;
  m.update(frame(2), std::nullopt, state);
  EXPECT_TRUE(state.messageIsError);
  EXPECT_NE(state.message.find("at least two references"), std::string::npos) << state.message;
  EXPECT_FALSE(m.map().has_value());
  state.addRequested = true;
  m.update(frame(2), std::nullopt, state);
  EXPECT_NE(state.message.find("Add to map needs a map"), std::string::npos) << state.message;
  EXPECT_FALSE(m.save(test::freshTempDir("live_mapping_nomap") / "map", state));
  EXPECT_NE(state.message.find("Build map first"), std::string::npos) << state.message;
}

TEST_F(LiveMappingTest, BuildsAddsAndSavesAMapAtTheTruePoses) {
  MapState state;
  LiveMapping m = mapping(state);
  ASSERT_TRUE(m.capture(frame(0), std::nullopt, state)) << state.message;
  ASSERT_TRUE(m.capture(frame(30), std::nullopt, state)) << state.message;
  ASSERT_EQ(state.pairs.size(), 1u);
  EXPECT_GT(state.pairs[0].distanceMetres, 0.01);
  EXPECT_TRUE(state.pairs[0].warning.empty()) << state.pairs[0].warning;
  ASSERT_TRUE(m.buildNow(state)) << state.message;
  std::optional<MultiReferenceMap> map = m.takeMapForTracking();
  ASSERT_TRUE(map.has_value());
  EXPECT_FALSE(m.takeMapForTracking().has_value());  // handed over once
  ASSERT_EQ(map->size(), 2);
  EXPECT_EQ(state.mapReferences, 2);
  EXPECT_GT(state.mapPoints, 100u);
  for (int v = 0; v < 2; ++v) {
    const RigidPose truth = sim_->framePose(v * 30);
    const RigidPose& T = map->views[static_cast<std::size_t>(v)].T;
    EXPECT_LT(RigidPose::translationDistance(T.inverse(), truth.inverse()), 0.003) << v;
    EXPECT_LT(RigidPose::rotationDistance(T, truth) * kRadToDeg, 0.2) << v;
  }

  // Track to frame 70, then cover the marker (a grey patch over its truth projection) and capture
  // it posed by tracking; Add to map puts it in with extend's matching + bundle adjustment.
  PoseFrameTracker tracker(*map, TrackerParams{});
  TrackingResult r;
  for (int k = 0; k <= 70; ++k) r = tracker.process(sim_->renderFrame(k), k, k / 30.0);
  ASSERT_TRUE(r.worldToCamera.has_value()) << r.status;
  Frame covered = frame(70);
  std::vector<cv::Point> marker;
  for (const Eigen::Vector3d& c : sim_->marker().cornersWorld()) {
    const Eigen::Vector2d p =
        sim_->camera().projectDistorted(sim_->framePose(70) * Eigen::Vector3d(1.3 * c));
    marker.emplace_back(cvRound(p.x()), cvRound(p.y()));
  }
  cv::fillConvexPoly(covered.image, marker, cv::Scalar(128, 128, 128));
  ASSERT_TRUE(m.capture(covered, r.worldToCamera, state)) << state.message;
  EXPECT_EQ(state.captures.back().poseFrom, "tracking");
  state.addRequested = true;
  m.update(covered, r.worldToCamera, state);
  ASSERT_FALSE(state.messageIsError) << state.message;
  map = m.takeMapForTracking();
  ASSERT_TRUE(map.has_value()) << state.message;
  ASSERT_EQ(map->size(), 3);
  EXPECT_TRUE(state.captures.back().inMap);
  const RigidPose truth = sim_->framePose(70);
  const RigidPose& added = map->views[2].T;
  const double addedMm = RigidPose::translationDistance(added.inverse(), truth.inverse()) * 1000;
  RecordProperty("added_reference_centre_error_um", static_cast<int>(addedMm * 1000));
  EXPECT_LT(addedMm, 3.0);
  for (int v = 0; v < 2; ++v)  // the world frame is held: the built references do not move
    EXPECT_TRUE(map->views[static_cast<std::size_t>(v)].anchored);

  const std::filesystem::path dir = test::freshTempDir("live_mapping_save");
  ASSERT_TRUE(m.save(dir / "map", state)) << state.message;
  const MultiReferenceMap loaded = MultiReferenceMap::load(dir / "map");
  EXPECT_EQ(loaded.size(), 3);
  EXPECT_EQ(loaded.points.size(), map->points.size());
  // Saved again over it: replaced whole, and no staging folder left behind.
  ASSERT_TRUE(m.save(dir / "map", state)) << state.message;
  EXPECT_EQ(MultiReferenceMap::load(dir / "map").size(), 3);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            1);

  // A full disk (a 64 KiB file-size limit: writes fail with EFBIG like ENOSPC): a clear message,
  // no new folder, the existing one untouched.
  struct rlimit old {};
  getrlimit(RLIMIT_FSIZE, &old);
  const auto previous = signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = old;
  small.rlim_cur = 64 * 1024;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  const bool saved = m.save(dir / "other", state);
  const bool replaced = m.save(dir / "map", state);
  setrlimit(RLIMIT_FSIZE, &old);
  signal(SIGXFSZ, previous);
  EXPECT_FALSE(saved);
  EXPECT_FALSE(replaced);
  EXPECT_TRUE(state.messageIsError);
  EXPECT_NE(state.message.find("failed, nothing written (is the disk full?)"), std::string::npos)
      << state.message;
  EXPECT_FALSE(std::filesystem::exists(dir / "other"));
  EXPECT_EQ(MultiReferenceMap::load(dir / "map").size(), 3);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            1);
}

TEST_F(LiveMappingTest, BuildsOnAWorkerThreadWhileTheLoopGoesOn) {
  MapState state;
  LiveMapping m = mapping(state, true);
  ASSERT_TRUE(m.capture(frame(0), std::nullopt, state));
  ASSERT_TRUE(m.capture(frame(30), std::nullopt, state));
  state.buildRequested = true;
  m.update(frame(31), std::nullopt, state);
  // The request returned with the build under way: no map yet, the loop goes on (a build in
  // the request's own thread would return with the map built and `working` false).
  EXPECT_TRUE(state.working);
  EXPECT_FALSE(m.takeMapForTracking().has_value());
  EXPECT_EQ(state.workLabel, "building the map");
  EXPECT_NE(state.progressText.find(" of 1 pairs matched, "), std::string::npos)
      << state.progressText;
  // A second request while it runs is refused with a message.
  state.buildRequested = true;
  m.update(frame(32), std::nullopt, state);
  EXPECT_NE(state.message.find("busy"), std::string::npos) << state.message;
  int loops = 0;
  while (state.working && loops < 6000) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    m.update(frame(33), std::nullopt, state);
    ++loops;
  }
  ASSERT_FALSE(state.working);
  EXPECT_GT(loops, 0);  // updates went on while the worker built the map
  EXPECT_FALSE(state.messageIsError) << state.message;
  EXPECT_TRUE(m.takeMapForTracking().has_value());
}

// Unprepared (no marker): the first capture, a view turned on the spot refused with the motion
// shown, a capture from another place accepted, a third refused until the map is built, Build map
// refused without the baseline and built with it (the captures then posed by the map), and after
// it captures posed only by tracking.
TEST_F(LiveMappingTest, UnpreparedCapturesAreCheckedAndTheMapBuiltWithTheBaseline) {
  MapState state;
  LiveMapping m(sim_->camera(), MapExtenderParams{}, UnpreparedMapParams{}, false, state);
  EXPECT_TRUE(state.unprepared);
  EXPECT_NE(state.fiducial.find("unprepared"), std::string::npos) << state.fiducial;
  const Frame blank{cv::Mat(sim_->camera().imageSize(), CV_8UC3, cv::Scalar(90, 90, 90)), 5, 0.0};
  EXPECT_FALSE(m.capture(blank, std::nullopt, state));
  EXPECT_NE(state.message.find("cannot capture frame 5: the captured view is textureless"),
            std::string::npos)
      << state.message;
  ASSERT_TRUE(m.capture(frame(0), std::nullopt, state)) << state.message;
  EXPECT_NE(state.message.find("now move the camera sideways"), std::string::npos);
  EXPECT_EQ(state.captures[0].poseFrom, "matches");
  EXPECT_TRUE(state.pairs.empty());

  // Frame 0's camera turned 4 degrees on the spot.
  const RigidPose turned =
      RigidPose(Eigen::AngleAxisd(4.0 / kRadToDeg, Eigen::Vector3d::UnitY()).toRotationMatrix(),
                Eigen::Vector3d::Zero()) *
      sim_->framePose(0);
  const Frame turnedFrame{sim_->renderView(turned, 7, 2.0), 6, 0.2};
  EXPECT_FALSE(m.capture(turnedFrame, std::nullopt, state));
  EXPECT_NE(state.message.find("cannot capture frame 6: the camera turned but hardly moved"),
            std::string::npos)
      << state.message;
  EXPECT_FALSE(state.motionUsable);
  EXPECT_EQ(state.motionFrame, 6);
  EXPECT_NE(state.motion.find("a rotation alone explains"), std::string::npos) << state.motion;
  EXPECT_EQ(state.captures.size(), 1u);

  ASSERT_TRUE(m.capture(frame(30), std::nullopt, state)) << state.message;
  EXPECT_TRUE(state.motionUsable);
  EXPECT_NE(state.message.find("type the distance the camera moved"), std::string::npos);
  EXPECT_FALSE(m.capture(frame(60), std::nullopt, state));
  EXPECT_NE(state.message.find("Build map first"), std::string::npos) << state.message;

  state.buildRequested = true;
  m.update(frame(31), std::nullopt, state);
  EXPECT_TRUE(state.messageIsError);
  EXPECT_NE(state.message.find("Build map needs the distance the camera moved"), std::string::npos)
      << state.message;
  EXPECT_FALSE(m.map().has_value());

  const RigidPose A = sim_->framePose(0), B = sim_->framePose(30);
  state.baselineMetres = (A.cameraCentre() - B.cameraCentre()).norm();
  ASSERT_TRUE(m.buildNow(state)) << state.message;
  std::optional<MultiReferenceMap> map = m.takeMapForTracking();
  ASSERT_TRUE(map.has_value());
  EXPECT_NE(state.message.find("map built from the captures' own matches"), std::string::npos)
      << state.message;
  // The captures are posed now: their pair's distance is the baseline typed in.
  ASSERT_EQ(state.pairs.size(), 1u);
  EXPECT_NEAR(state.pairs[0].distanceMetres, state.baselineMetres, 1e-9);
  const RigidPose relative = map->views[1].T * map->views[0].T.inverse(), truth = B * A.inverse();
  const double turn = RigidPose::rotationDistance(relative, truth) * kRadToDeg;
  RecordProperty("relative_rotation_error_udeg", static_cast<int>(turn * 1e6));
  EXPECT_LT(turn, 0.1);
  EXPECT_LT(RigidPose::translationDistance(relative, truth), 0.002);

  // With the map built, a capture needs the tracker's pose.
  EXPECT_FALSE(m.capture(frame(60), std::nullopt, state));
  EXPECT_NE(state.message.find("not tracking"), std::string::npos) << state.message;
  state.clearRequested = true;
  m.update(frame(61), std::nullopt, state);
  EXPECT_TRUE(state.captures.empty());
  EXPECT_TRUE(state.motion.empty());
}

// In the window the motion since the first capture is measured on the worker thread while the
// frames go on, and shown.
TEST_F(LiveMappingTest, UnpreparedMotionIsMeasuredLiveOnAWorkerThread) {
  MapState state;
  LiveMapping m(sim_->camera(), MapExtenderParams{}, UnpreparedMapParams{}, true, state);
  ASSERT_TRUE(m.capture(frame(0), std::nullopt, state)) << state.message;
  const Frame later = frame(30);
  for (int loops = 0; state.motion.empty() && loops < 3000; ++loops) {
    m.update(later, std::nullopt, state);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_FALSE(state.motion.empty());
  EXPECT_EQ(state.motionFrame, 30);
  EXPECT_TRUE(state.motionUsable) << state.motion;
  EXPECT_NE(state.motion.find("keypoint matches"), std::string::npos) << state.motion;
}

}  // namespace
}  // namespace reftrack::app
