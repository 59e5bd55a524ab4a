#include "app/tracking/HomographyTrack.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>

#include "TestPaths.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "render/context/GlContext.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

// A folder of 8 noisy frames of the static camera plus reference view A, 320x240.
std::filesystem::path writeStaticSequence(const std::string& name) {
  const auto dir = test::freshTempDir(name);
  const auto context = render::createHeadlessContext();
  SimulationOptions o;
  o.preset = "static";
  o.frames = 8;
  o.size = {320, 240};
  SceneSimulator sim(o);
  std::filesystem::create_directories(dir / "frames");
  cv::imwrite((dir / "reference.png").string(), sim.renderReference('A'));
  for (int k = 0; k < o.frames; ++k) {
    char file[32];
    std::snprintf(file, sizeof file, "%06d.png", k);
    cv::imwrite((dir / "frames" / file).string(), sim.renderFrame(k));
  }
  std::ofstream(dir / "labels.yml") << "labels:\n  - { text: \"Lamp\", x: 150, y: 90 }\n";
  return dir;
}

}  // namespace

TEST(HomographyTrack, WritesOneCsvRowPerFrameAndARecording) {
  const auto dir = writeStaticSequence("HomographyTrack_ok");
  HomographyTrackOptions o;
  o.reference = dir / "reference.png";
  o.input = (dir / "frames").string();
  o.labels = dir / "labels.yml";
  o.csv = dir / "track.csv";
  o.record = dir / "track.mp4";
  const HomographyTrackSummary s = runHomographyTrack(o);
  EXPECT_EQ(s.frames, 8);
  EXPECT_EQ(s.tracked, 8);
  EXPECT_GT(s.medianMs, 0.0);
  std::ifstream in(o.csv);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 9u);
  EXPECT_EQ(lines[1].substr(0, 19), "0,0.000000,tracked,");
  EXPECT_GT(std::filesystem::file_size(o.record), 1000u);
  o.maxFrames = 3;
  o.record.clear();
  EXPECT_EQ(runHomographyTrack(o).frames, 3);
}

TEST(HomographyTrack, LostFramesCarryTheirReasonInTheCsv) {
  // Frame 3 black: lost, with the reason; the others tracked, with an empty reason (frame 4 is
  // registered cold again).
  const auto dir = writeStaticSequence("HomographyTrack_reason");
  cv::imwrite((dir / "frames" / "000003.png").string(), cv::Mat(240, 320, CV_8UC3, cv::Scalar(0)));
  HomographyTrackOptions o;
  o.reference = dir / "reference.png";
  o.input = (dir / "frames").string();
  o.csv = dir / "track.csv";
  const HomographyTrackSummary s = runHomographyTrack(o);
  EXPECT_EQ(s.tracked, 7);
  std::ifstream in(o.csv);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 9u);
  EXPECT_EQ(lines[0].substr(lines[0].size() - 7), ",reason");
  for (size_t k = 1; k < lines.size(); ++k) {
    if (k == 4) {
      EXPECT_EQ(lines[k].substr(0, 2), "3,") << lines[k];
      EXPECT_NE(lines[k].find(",lost,"), std::string::npos) << lines[k];
      EXPECT_NE(lines[k].find(",\"too few corners (0): textureless, black or blurred frame\""),
                std::string::npos)
          << lines[k];
    } else {
      EXPECT_NE(lines[k].find(",tracked,"), std::string::npos) << lines[k];
      EXPECT_EQ(lines[k].substr(lines[k].size() - 3), ",\"\"") << lines[k];
    }
  }
}

// A reference photographed by another camera: the static clip's reference view upscaled to
// 512x384 (a finer picture of the same view) tracks the 320x240 frames, with or without the
// frames' camera file; H maps the reference's pixels into the frames (the truth: the scale
// 320/512 between the two, as the static camera does not move; 2 grey levels of noise), the
// recording has the frames' size and the label lands where the scaled position puts it.
TEST(HomographyTrack, TracksAReferenceOfAnotherSizeThanTheFrames) {
  const auto dir = writeStaticSequence("HomographyTrack_sizes");
  cv::Mat big = cv::imread((dir / "reference.png").string());
  cv::resize(big, big, {512, 384}, 0, 0, cv::INTER_CUBIC);
  cv::imwrite((dir / "big.png").string(), big);
  std::ofstream(dir / "big-labels.yml") << "labels:\n  - { text: \"Lamp\", x: 240, y: 144 }\n";
  PinholeCamera::fromFieldOfView({320, 240}, 60.0).save(dir / "camera.yml");
  for (const bool camera : {false, true}) {
    HomographyTrackOptions o;
    o.reference = dir / "big.png";
    o.input = (dir / "frames").string();
    o.labels = dir / "big-labels.yml";
    o.csv = dir / "track.csv";
    o.record = dir / "track.mp4";
    if (camera) o.camera = dir / "camera.yml";
    const HomographyTrackSummary s = runHomographyTrack(o);
    EXPECT_EQ(s.frames, 8);
    EXPECT_EQ(s.tracked, 8) << (camera ? "with" : "without") << " the camera";
    std::ifstream in(o.csv);
    std::string header, row;
    std::getline(in, header);
    while (std::getline(in, row)) {
      // index,timestamp,status,inlier_ratio,h11..h33: h11 and h22 near 320 / 512 = 0.625.
      std::vector<double> v;
      std::stringstream fields(row);
      for (std::string f; std::getline(fields, f, ',');) v.push_back(std::atof(f.c_str()));
      ASSERT_GE(v.size(), 13u);
      const cv::Matx33d H(v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11], v[12]);
      // The label at (240, 144) of the big reference is at (149.6, 89.8) in the frames
      // (x_small = (x_big + 0.5) * 0.625 - 0.5).
      const cv::Vec3d q = H * cv::Vec3d(240, 144, 1);
      EXPECT_NEAR(q[0] / q[2], 149.8125, 0.3) << row;
      EXPECT_NEAR(q[1] / q[2], 89.8125, 0.3) << row;
    }
    const cv::Mat first = [&] {
      cv::VideoCapture video(o.record.string());
      cv::Mat f;
      video >> f;
      return f;
    }();
    EXPECT_EQ(first.size(), cv::Size(320, 240));
  }
}

// Photos from several cameras in one folder (the issue's `--input <folder with imgN>`): frames of
// 320x240 and of 480x360 (the same views enlarged), each registered; the recording keeps the
// first frame's size, the larger frames fitted into it.
TEST(HomographyTrack, TracksAFolderOfFramesOfSeveralSizes) {
  const auto dir = writeStaticSequence("HomographyTrack_mixed");
  for (int k : {2, 5}) {
    char file[32];
    std::snprintf(file, sizeof file, "%06d.png", k);
    cv::Mat f = cv::imread((dir / "frames" / file).string());
    cv::resize(f, f, {480, 360}, 0, 0, cv::INTER_CUBIC);
    cv::imwrite((dir / "frames" / file).string(), f);
  }
  HomographyTrackOptions o;
  o.reference = dir / "reference.png";
  o.input = (dir / "frames").string();
  o.csv = dir / "track.csv";
  o.record = dir / "track.mp4";
  const HomographyTrackSummary s = runHomographyTrack(o);
  EXPECT_EQ(s.frames, 8);
  EXPECT_EQ(s.tracked, 8);
  std::ifstream in(o.csv);
  std::string row;
  std::getline(in, row);
  for (int k = 0; std::getline(in, row); ++k) {
    std::vector<double> v;
    std::stringstream fields(row);
    for (std::string f; std::getline(fields, f, ',');) v.push_back(std::atof(f.c_str()));
    ASSERT_GE(v.size(), 13u);
    // h11: 1 for the 320x240 frames, 1.5 for the enlarged ones.
    EXPECT_NEAR(v[4] / v[12], k == 2 || k == 5 ? 1.5 : 1.0, 0.01) << row;
  }
  cv::VideoCapture video(o.record.string());
  cv::Mat first;
  video >> first;
  EXPECT_EQ(first.size(), cv::Size(320, 240));
}

TEST(HomographyTrack, BadInputThrowsAndWritesNothing) {
  const auto dir = writeStaticSequence("HomographyTrack_bad");
  HomographyTrackOptions o;
  o.input = (dir / "frames").string();
  o.csv = dir / "track.csv";
  o.reference = dir / "missing.png";
  EXPECT_THROW(runHomographyTrack(o), Error);
  // A camera file of another size than the frames (the camera is the frames').
  o.reference = dir / "reference.png";
  PinholeCamera::fromFieldOfView({640, 480}, 60.0).save(dir / "camera.yml");
  o.camera = dir / "camera.yml";
  try {
    runHomographyTrack(o);
    FAIL() << "expected a size error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is 320x240 but the camera is calibrated for 640x480"),
              std::string::npos)
        << e.what();
  }
  o.camera.clear();
  o.labels = dir / "frames";  // not a labels file
  EXPECT_THROW(runHomographyTrack(o), Error);
  EXPECT_FALSE(std::filesystem::exists(o.csv));
}
