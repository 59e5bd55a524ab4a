// CalibrationSession: captures distinct views, rejects near duplicates and blank frames, tracks
// coverage, and calibrates (synthetic views from a known K; the OpenCV sample images).
#include "engine/calibration/CalibrationSession.hpp"

#include <gtest/gtest.h>

#include <numeric>

#include "TestPaths.hpp"
#include "engine/calibration/CalibrationInput.hpp"
#include "engine/calibration/SyntheticBoardViews.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {

const cv::Size kSize = test::kBoardViewSize;
constexpr int kPixelsPerSquare = 64;

CalibrationBoard chessboard() { return CalibrationBoard::parse("chessboard:9x6:0.025"); }

cv::Mat view(const CalibrationBoard& board, const RigidPose& pose, int seed) {
  static const cv::Mat texture = test::chessboardTexture(board, kPixelsPerSquare);
  return test::renderBoardView(board, texture, kPixelsPerSquare, test::boardViewK(), kSize, pose,
                               seed);
}

}  // namespace

TEST(CalibrationSession, RecoversIntrinsicsFromSyntheticViews) {
  const CalibrationBoard board = chessboard();
  CalibrationSessionParams params;
  // No lens distortion in the renderer; free p1, p2 entangle with the principal point over 15
  // views (see CameraCalibrator_test), so the tangential terms are fixed as there.
  params.calibration.zeroTangent = true;
  CalibrationSession session(board, kSize, params);
  int seed = 0;
  for (const RigidPose& pose : test::variedBoardPoses(board)) {
    const CalibrationViewOutcome out = session.addView(view(board, pose, seed++));
    EXPECT_TRUE(out.found) << "view " << seed;
    EXPECT_EQ(out.corners, 54);
    EXPECT_TRUE(out.accepted) << "view " << seed << ": " << out.reason;
  }
  EXPECT_EQ(session.capturedViews(), 15);
  EXPECT_EQ(session.rejectedViews(), 0);
  // Every captured corner is counted in exactly one cell.
  const std::vector<int>& cells = session.cellCounts();
  EXPECT_EQ(std::accumulate(cells.begin(), cells.end(), 0), 15 * 54);
  const CalibrationResult r = session.calibrate();
  ASSERT_EQ(r.views.size(), 15u);
  EXPECT_EQ(r.views[0].label, "view 1");
  // The bar: fx, fy, cx, cy within 0.5% of the rendering camera.
  test::expectIntrinsicsNear(r.camera, test::boardViewK(), 0.005);
  // Rendered corners are exact up to interpolation and 2-grey-level noise: well under 0.2 px.
  EXPECT_LT(r.rmsPx, 0.2);
  std::printf("session synthetic: fx %.3f fy %.3f cx %.3f cy %.3f rms %.4f px, coverage %.2f\n",
              r.camera.fx(), r.camera.fy(), r.camera.cx(), r.camera.cy(), r.rmsPx,
              session.coverage());

  // Saved as `reftrack calibrate` writes it: PinholeCamera::load reads the same K back.
  const auto dir = test::freshTempDir("CalibrationSession_Save");
  CalibrationSession::save(r, dir / "camera.yml");
  const PinholeCamera loaded = PinholeCamera::load(dir / "camera.yml");
  EXPECT_NEAR(loaded.fx(), r.camera.fx(), 1e-9);
  EXPECT_NEAR(loaded.cy(), r.camera.cy(), 1e-9);
  EXPECT_EQ(loaded.imageSize(), kSize);
}

TEST(CalibrationSession, RejectsNearDuplicatesAndBlankFrames) {
  const CalibrationBoard board = chessboard();
  CalibrationSession session(board, kSize);
  const RigidPose frontal = test::boardPose(board, 0, 0, 0, 0, 0, 0.55);
  ASSERT_TRUE(session.addView(view(board, frontal, 1)).accepted);
  // The same pose with other sensor noise, and the board moved by 3 mm (about 3 px at 0.55 m):
  // both far below the 12 px (1.5% of the 800 px diagonal) needed.
  CalibrationViewOutcome again = session.addView(view(board, frontal, 2));
  EXPECT_TRUE(again.found);
  EXPECT_FALSE(again.accepted);
  EXPECT_NE(again.reason.find("too similar to view 1"), std::string::npos) << again.reason;
  const RigidPose nudged = test::boardPose(board, 0, 0, 0, 0.003, 0, 0.55);
  EXPECT_FALSE(session.addView(view(board, nudged, 3)).accepted);
  // Turned by 180 degrees in the image plane: the detector may number the corners from the other
  // end, which must not make the same picture count as a new view.
  const RigidPose turned = test::boardPose(board, 0, 0, 180, 0, 0, 0.55);
  EXPECT_FALSE(session.addView(view(board, turned, 4)).accepted);
  // Moved by 6 cm (about 68 px): a new view.
  const RigidPose moved = test::boardPose(board, 0, 0, 0, 0.06, 0.0, 0.55);
  const CalibrationViewOutcome far = session.addView(view(board, moved, 5));
  EXPECT_TRUE(far.accepted) << far.reason;

  const CalibrationViewOutcome blank = session.addView(cv::Mat(kSize, CV_8UC1, cv::Scalar(90)));
  EXPECT_FALSE(blank.found);
  EXPECT_FALSE(blank.accepted);
  EXPECT_EQ(blank.reason, "board not found");
  EXPECT_EQ(session.lastRejection(), "board not found");
  EXPECT_EQ(session.capturedViews(), 2);
  EXPECT_EQ(session.rejectedViews(), 4);
  EXPECT_THROW(session.addView(cv::Mat(cv::Size(320, 240), CV_8UC1, cv::Scalar(0))), Error);

  session.clear();
  EXPECT_EQ(session.capturedViews(), 0);
  EXPECT_EQ(session.rejectedViews(), 0);
  EXPECT_EQ(session.coverage(), 0.0);
}

TEST(CalibrationSession, CoverageCountsTheCellsTouched) {
  const CalibrationBoard board = chessboard();
  CalibrationSession session(board, kSize);
  const RigidPose frontal = test::boardPose(board, 0, 0, 0, 0, 0, 0.55);
  const CalibrationViewOutcome out = session.addView(view(board, frontal, 1));
  ASSERT_TRUE(out.accepted);
  // Recount from the detected corners with the session's own cell rectangles.
  std::vector<int> expected(48, 0);
  for (const cv::Point2f& p : out.observation.imagePoints)
    for (int row = 0; row < 6; ++row)
      for (int col = 0; col < 8; ++col)
        if (session.cell(col, row).contains(p)) ++expected[static_cast<std::size_t>(row * 8 + col)];
  EXPECT_EQ(session.cellCounts(), expected);
  const double touched = static_cast<double>(
      std::count_if(expected.begin(), expected.end(), [](int c) { return c > 0; }));
  EXPECT_DOUBLE_EQ(session.coverage(), touched / 48.0);
  // The frontal board at 0.55 m spans about 220 x 140 px of the 640 x 480 image: some cells
  // but far from all.
  EXPECT_GT(session.coverage(), 0.05);
  EXPECT_LT(session.coverage(), 0.5);
  EXPECT_THROW(session.cell(8, 0), Error);
}

TEST(CalibrationSession, TooFewViewsIsAClearError) {
  const CalibrationBoard board = chessboard();
  CalibrationSession session(board, kSize);
  try {
    session.calibrate();
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("at least 4 captured views"), std::string::npos)
        << e.what();
  }
  session.addView(view(board, test::variedBoardPoses(board)[0], 1));
  session.addView(view(board, test::variedBoardPoses(board)[1], 2));
  try {
    session.calibrate();
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("have 2"), std::string::npos) << e.what();
  }
  CalibrationSessionParams bad;
  bad.minMeanShift = -0.1;
  EXPECT_THROW(CalibrationSession(board, kSize, bad), Error);
  bad = {};
  bad.coverageGrid = {0, 6};
  EXPECT_THROW(CalibrationSession(board, kSize, bad), Error);
  EXPECT_THROW(CalibrationSession(board, cv::Size(0, 0)), Error);
}

TEST(CalibrationSession, MatchesOpenCvSampleCalibrationOnRealImages) {
  const auto data = test::sharedDataDir();
  if (!data) GTEST_SKIP() << "../shared/data is absent";
  const auto dir = *data / "chessboard-calib";
  CalibrationSessionParams params;
  params.calibration.fixAspectRatio = true;  // as OpenCV's sample did (flags: 2)
  CalibrationSession session(chessboard(), kSize, params);
  CalibrationInput input((dir / "left*.jpg").string());
  cv::Mat img, first;
  std::string label;
  while (input.next(img, label)) {
    const CalibrationViewOutcome out = session.addView(img);
    EXPECT_TRUE(out.accepted) << label << ": " << out.reason;
    if (first.empty()) first = img.clone();
  }
  // The 13 hand-held shots are all distinct; offering the first again is a duplicate.
  EXPECT_EQ(session.capturedViews(), 13);
  EXPECT_FALSE(session.addView(first).accepted);
  EXPECT_EQ(session.rejectedViews(), 1);
  const CalibrationResult r = session.calibrate();
  const PinholeCamera ref = PinholeCamera::load(dir / "left_intrinsics.yml");
  std::printf(
      "session real left*.jpg: %zu views, fx %.3f fy %.3f cx %.3f cy %.3f rms %.4f px, "
      "coverage %.2f (OpenCV sample: fx %.3f cx %.3f cy %.3f)\n",
      r.views.size(), r.camera.fx(), r.camera.fy(), r.camera.cx(), r.camera.cy(), r.rmsPx,
      session.coverage(), ref.fx(), ref.cx(), ref.cy());
  // Same images and model as OpenCV's sample but a different corner detector (SB + cornerSubPix
  // vs the classic one); the sample's K is itself uncertain by a few pixels (13 views, strong
  // k3), so 1% on f and 2% of the width on the principal point, as for CameraCalibrator.
  EXPECT_NEAR(r.camera.fx(), ref.fx(), 0.01 * ref.fx());
  EXPECT_NEAR(r.camera.fy(), ref.fy(), 0.01 * ref.fy());
  EXPECT_NEAR(r.camera.cx(), ref.cx(), 0.02 * 640);
  EXPECT_NEAR(r.camera.cy(), ref.cy(), 0.02 * 640);
  EXPECT_LT(r.rmsPx, 0.5);
}
