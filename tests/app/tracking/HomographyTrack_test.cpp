#include "app/tracking/HomographyTrack.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "TestPaths.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "engine/core/Error.hpp"
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

TEST(HomographyTrack, BadInputThrowsAndWritesNothing) {
  const auto dir = writeStaticSequence("HomographyTrack_bad");
  HomographyTrackOptions o;
  o.input = (dir / "frames").string();
  o.csv = dir / "track.csv";
  o.reference = dir / "missing.png";
  EXPECT_THROW(runHomographyTrack(o), Error);
  // A reference of another size than the frames.
  cv::imwrite((dir / "small.png").string(), cv::Mat(120, 160, CV_8UC3, cv::Scalar(1, 2, 3)));
  cv::Mat big = cv::imread((dir / "reference.png").string());
  cv::resize(big, big, {640, 480});
  cv::imwrite((dir / "big.png").string(), big);
  o.reference = dir / "big.png";
  try {
    runHomographyTrack(o);
    FAIL() << "expected a size error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("640x480"), std::string::npos) << e.what();
  }
  o.reference = dir / "reference.png";
  o.labels = dir / "frames";  // not a labels file
  EXPECT_THROW(runHomographyTrack(o), Error);
  EXPECT_FALSE(std::filesystem::exists(o.csv));
}
