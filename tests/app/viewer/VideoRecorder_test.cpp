// VideoRecorder: N frames in, an MP4 of exactly N frames at the given rate plus the TUM
// trajectory beside it; nothing left behind when a recording is abandoned or fails.
#include "app/viewer/VideoRecorder.hpp"

#include <gtest/gtest.h>

#include <opencv2/videoio.hpp>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;
namespace fs = std::filesystem;

namespace {

int countFramesByDecoding(const fs::path& file) {
  cv::VideoCapture capture(file.string(), cv::CAP_FFMPEG);
  int n = 0;
  cv::Mat image;
  while (capture.read(image)) ++n;
  return n;
}

}  // namespace

TEST(VideoRecorder, WritesEveryFrameAndTheTrajectory) {
  const fs::path dir = test::freshTempDir("VideoRecorder_Write");
  const fs::path mp4 = dir / "run.mp4";
  {
    VideoRecorder recorder(mp4, 25.0, {96, 64});
    for (int k = 0; k < 17; ++k) {
      std::optional<RigidPose> pose;
      if (k != 3) pose = RigidPose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.01 * k, 0, 1));
      recorder.write(cv::Mat(64, 96, CV_8UC3, cv::Scalar(10 * k, 0, 0)), k / 25.0, pose);
    }
    EXPECT_FALSE(fs::exists(mp4));  // only renamed into place by close()
    recorder.close();
    EXPECT_EQ(recorder.trajectoryPath(), dir / "run_trajectory.txt");
  }
  ASSERT_TRUE(fs::exists(mp4));
  EXPECT_EQ(countFramesByDecoding(mp4), 17);
  cv::VideoCapture capture(mp4.string(), cv::CAP_FFMPEG);
  EXPECT_DOUBLE_EQ(capture.get(cv::CAP_PROP_FPS), 25.0);
  const TumTrajectory t = TumTrajectory::load(dir / "run_trajectory.txt");
  ASSERT_EQ(t.poses.size(), 16u);  // frame 3 had no pose
  EXPECT_NEAR(t.poses[3].timestamp, 4 / 25.0, 1e-6);
  EXPECT_NEAR(t.poses[3].worldToCamera.translation().x(), 0.04, 1e-9);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_TRUE(e.path() == mp4 || e.path() == dir / "run_trajectory.txt") << e.path();
}

TEST(VideoRecorder, AbandonedOrFailedRecordingLeavesNoFile) {
  const fs::path dir = test::freshTempDir("VideoRecorder_Abandon");
  {
    VideoRecorder recorder(dir / "a.mp4", 30.0, {32, 32});
    recorder.write(cv::Mat(32, 32, CV_8UC3, cv::Scalar::all(0)), 0.0, std::nullopt);
    EXPECT_THROW(recorder.write(cv::Mat(16, 16, CV_8UC3), 0.1, std::nullopt), Error);
  }
  EXPECT_TRUE(fs::is_empty(dir));
  EXPECT_THROW(VideoRecorder(dir / "a.avi", 30.0, {32, 32}), Error);
  EXPECT_THROW(VideoRecorder(dir / "missing" / "a.mp4", 30.0, {32, 32}), Error);
  EXPECT_THROW(VideoRecorder(dir / "a.mp4", 0.0, {32, 32}), Error);
  {
    VideoRecorder empty(dir / "b.mp4", 30.0, {32, 32});
    EXPECT_THROW(empty.close(), Error);  // no frame: nothing to keep
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

// closeRecording hands a recording's failure back as its message (the caller still writes its
// other outputs) and finishes a good one like close().
TEST(VideoRecorder, CloseRecordingReturnsTheFailureInsteadOfThrowing) {
  const fs::path dir = test::freshTempDir("VideoRecorder_CloseRecording");
  EXPECT_EQ(closeRecording(nullptr), "");
  VideoRecorder empty(dir / "empty.mp4", 30.0, {32, 32});
  EXPECT_NE(closeRecording(&empty).find("holds no frame"), std::string::npos);
  VideoRecorder good(dir / "good.mp4", 30.0, {32, 32});
  good.write(cv::Mat(32, 32, CV_8UC3, cv::Scalar::all(90)), 0.0, std::nullopt);
  EXPECT_EQ(closeRecording(&good), "");
  EXPECT_TRUE(fs::is_regular_file(dir / "good.mp4"));
  EXPECT_FALSE(fs::exists(dir / "empty.mp4"));
}
