// LiveCalibration: carries out the Calibration panel's requests on synthetic board frames -
// capture, auto-capture, clear, board change, calibrate (in line and on a worker thread), save,
// use for tracking - and reports failures as messages instead of throwing.
#include "app/viewer/LiveCalibration.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "TestPaths.hpp"
#include "engine/calibration/SyntheticBoardViews.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

const cv::Size kSize = test::kBoardViewSize;

// The viewer's frames are BGR.
std::vector<Frame> boardFrames(int count) {
  const CalibrationBoard board = CalibrationBoard::parse("chessboard:9x6:0.025");
  const cv::Mat texture = test::chessboardTexture(board, 64);
  const std::vector<RigidPose> poses = test::variedBoardPoses(board);
  std::vector<Frame> frames;
  for (int i = 0; i < count; ++i) {
    Frame f;
    cv::cvtColor(test::renderBoardView(board, texture, 64, test::boardViewK(), kSize, poses[i], i),
                 f.image, cv::COLOR_GRAY2BGR);
    f.index = i;
    frames.push_back(std::move(f));
  }
  return frames;
}

}  // namespace

TEST(LiveCalibration, CapturesCalibratesSavesAndHandsTheCameraOver) {
  const auto dir = test::freshTempDir("LiveCalibration_InLine");
  const std::vector<Frame> frames = boardFrames(6);
  CalibrationState state;
  LiveCalibration live(kSize, false, state);
  EXPECT_EQ(state.board, "chessboard:9x6:0.025");

  // Frame 0 is analysed but not captured until asked.
  live.update(frames[0], 1, state);
  EXPECT_EQ(state.currentCorners, 54);
  EXPECT_EQ(state.captured, 0);
  state.captureRequested = true;
  live.update(frames[0], 1, state);
  EXPECT_EQ(state.captured, 1);
  // The same frame again is a near duplicate, with the reason shown.
  state.captureRequested = true;
  live.update(frames[0], 2, state);
  EXPECT_EQ(state.captured, 1);
  EXPECT_EQ(state.rejected, 1);
  EXPECT_NE(state.lastRejection.find("too similar"), std::string::npos) << state.lastRejection;

  // Too few views: calibration fails with a message, nothing thrown.
  state.calibrateRequested = true;
  live.update(frames[0], 2, state);
  EXPECT_FALSE(state.result);
  EXPECT_NE(state.message.find("at least 4"), std::string::npos) << state.message;
  state.saveRequested = true;
  live.update(frames[0], 2, state);
  EXPECT_NE(state.message.find("calibrate first"), std::string::npos) << state.message;

  // Auto-capture every frame takes the remaining distinct views.
  state.autoCapture = true;
  state.autoCaptureEvery = 1;
  for (int i = 1; i < 6; ++i) live.update(frames[i], 2 + i, state);
  EXPECT_EQ(state.captured, 6);
  EXPECT_GT(state.coverage, 0.0);

  state.calibrateRequested = true;
  live.update(frames[5], 7, state);
  ASSERT_TRUE(state.result) << state.message;
  EXPECT_EQ(state.result->views.size(), 6u);
  // Six views with free tangential terms: K within 2% (the 15-view bar of 0.5% is checked by
  // CalibrationSession_test; here it is only shown that this is the camera of the frames).
  EXPECT_NEAR(state.result->camera.fx(), 620.0, 0.02 * 620.0);
  EXPECT_NEAR(state.result->camera.cy(), 236.8, 0.02 * 480.0);

  state.savePath = (dir / "camera.yml").string();
  state.saveRequested = true;
  live.update(frames[5], 7, state);
  EXPECT_EQ(state.message, "saved " + state.savePath);
  EXPECT_NEAR(PinholeCamera::load(dir / "camera.yml").fx(), state.result->camera.fx(), 1e-9);
  state.savePath = (dir / "no-such-folder" / "camera.yml").string();
  state.saveRequested = true;
  live.update(frames[5], 7, state);
  EXPECT_NE(state.message.find("no-such-folder"), std::string::npos) << state.message;

  EXPECT_FALSE(live.takeCameraForTracking());
  state.useForTrackingRequested = true;
  live.update(frames[5], 7, state);
  const std::optional<PinholeCamera> camera = live.takeCameraForTracking();
  ASSERT_TRUE(camera);
  EXPECT_EQ(camera->fx(), state.result->camera.fx());
  EXPECT_FALSE(live.takeCameraForTracking());  // handed over once

  state.clearRequested = true;
  live.update(frames[5], 7, state);
  EXPECT_EQ(state.captured, 0);
  EXPECT_EQ(state.coverage, 0.0);
}

TEST(LiveCalibration, BoardChangesAndBadBoardsAreReported) {
  const std::vector<Frame> frames = boardFrames(1);
  CalibrationState state;
  state.boardText = "chessboard:7x5:0.03";
  LiveCalibration live(kSize, false, state);
  live.update(frames[0], 1, state);
  EXPECT_EQ(state.currentCorners, 0);  // a 9x6 board is not a 7x5 one
  state.boardText = "chessboard:9x";
  state.applyBoardRequested = true;
  live.update(frames[0], 1, state);
  EXPECT_NE(state.message.find("chessboard:9x"), std::string::npos) << state.message;
  EXPECT_EQ(state.board, "chessboard:7x5:0.03");  // the old board stays in use
  state.boardText = "chessboard:9x6:0.025";
  state.applyBoardRequested = true;
  live.update(frames[0], 1, state);
  EXPECT_EQ(state.board, "chessboard:9x6:0.025");
  EXPECT_EQ(state.currentCorners, 54);  // the frame is analysed again for the new board
  CalibrationState bad;
  bad.boardText = "nonsense";
  EXPECT_THROW(LiveCalibration(kSize, false, bad), reftrack::Error);
}

TEST(LiveCalibration, BackgroundWorkDoesNotBlockUpdates) {
  const std::vector<Frame> frames = boardFrames(5);
  CalibrationState state;
  state.autoCapture = true;
  state.autoCaptureEvery = 1;
  LiveCalibration live(kSize, true, state);
  // Detection runs on a worker thread: each frame is shown until its detection has been
  // collected (bounded wait so a broken worker fails the test instead of hanging it).
  int number = 0;
  for (const Frame& f : frames) {
    ++number;
    const int before = state.captured + state.rejected;
    for (int k = 0; k < 3000 && state.captured + state.rejected == before; ++k) {
      live.update(f, number, state);
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  EXPECT_EQ(state.captured, 5) << state.lastRejection;
  state.calibrateRequested = true;
  live.update(frames[4], number, state);
  // The request returns at once with the calibration running (or, on a fast machine, already
  // collected on the next update).
  bool sawRunning = state.calibrating;
  for (int k = 0; k < 3000 && !state.result && state.message.empty(); ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    live.update(frames[4], number, state);
    sawRunning |= state.calibrating;
  }
  EXPECT_TRUE(sawRunning);
  ASSERT_TRUE(state.result) << state.message;
  EXPECT_FALSE(state.calibrating);
  EXPECT_EQ(state.result->views.size(), 5u);
}
