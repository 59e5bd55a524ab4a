// openFrameSource: each SRC form opens the right kind of source; bad ones say what is wrong.
#include "app/sources/FrameSourceFactory.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "DatasetFixtures.hpp"
#include "ErrorMessage.hpp"
#include "TestPaths.hpp"
#include "app/sources/EurocSequenceSource.hpp"
#include "app/sources/ImageFolderSource.hpp"
#include "app/sources/SimulatorSource.hpp"
#include "app/sources/TumSequenceSource.hpp"
#include "app/sources/VideoFileSource.hpp"
#include "engine/core/Error.hpp"
#include "render/context/GlContext.hpp"

using namespace reftrack;
using namespace reftrack::app;
namespace fs = std::filesystem;

namespace {

std::string errorOf(const std::string& input) {
  return test::errorMessage([&] { openFrameSource(input); });
}

}  // namespace

TEST(FrameSourceFactory, FoldersAndGlobsAreImageSources) {
  const fs::path dir = test::freshTempDir("FrameSourceFactory_Images");
  for (int k = 0; k < 3; ++k)
    cv::imwrite((dir / (std::to_string(k) + ".png")).string(), cv::Mat(8, 8, CV_8UC3));
  FrameSourceOptions options;
  options.imageFps = 12.0;
  const auto folder = openFrameSource(dir.string(), options);
  EXPECT_NE(dynamic_cast<ImageFolderSource*>(folder.get()), nullptr);
  EXPECT_DOUBLE_EQ(folder->fps(), 12.0);
  const auto glob = openFrameSource((dir / "[01].png").string());
  EXPECT_EQ(glob->frameCount(), 2);
}

TEST(FrameSourceFactory, SimulatorInputUsesTheOptions) {
  const auto context = render::createHeadlessContext();
  FrameSourceOptions options;
  options.simFrames = 4;
  options.simSize = {96, 72};
  EXPECT_TRUE(isSimulatorInput("sim:static"));
  const auto source = openFrameSource("sim:static", options);
  auto* sim = dynamic_cast<SimulatorSource*>(source.get());
  ASSERT_NE(sim, nullptr);
  EXPECT_EQ(sim->frameCount(), 4);
  EXPECT_EQ(sim->camera().imageSize(), cv::Size(96, 72));
}

TEST(FrameSourceFactory, DatasetPrefixesOpenTheDatasetSources) {
  const fs::path dir = test::freshTempDir("FrameSourceFactory_Datasets");
  test::writeTumSequence(dir / "tum", {cv::Mat(8, 8, CV_8UC3)}, {1305031102.5}, {});
  test::writeEurocSequence(dir / "euroc", {cv::Mat(8, 8, CV_8UC1)}, {1403636579763555584LL},
                           PinholeCamera::fromFieldOfView({8, 8}, 60.0), RigidPose(), {});
  const auto tum = openFrameSource("tum:" + (dir / "tum").string());
  EXPECT_NE(dynamic_cast<TumSequenceSource*>(tum.get()), nullptr);
  EXPECT_DOUBLE_EQ(tum->next()->timestamp, 1305031102.5);
  const auto euroc = openFrameSource("euroc:" + (dir / "euroc").string());
  EXPECT_NE(dynamic_cast<EurocSequenceSource*>(euroc.get()), nullptr);
  EXPECT_NEAR(euroc->next()->timestamp, 1403636579.763555584, 3e-7);
  // The folder of a layout is not an image folder: the prefix is what selects the reader.
  EXPECT_NE(errorOf("tum:" + (dir / "euroc").string()).find("has no rgb.txt"), std::string::npos);
  EXPECT_NE(errorOf("euroc:" + (dir / "tum").string()).find("expected DIR/mav0/cam0"),
            std::string::npos);
  EXPECT_NE(errorOf("euroc:/no/such/dir").find("does not exist"), std::string::npos);
}

TEST(FrameSourceFactory, BadInputsAreExplained) {
  EXPECT_NE(errorOf("sim:spiral").find("unknown simulator preset"), std::string::npos);
  EXPECT_NE(errorOf("camera:").find("expected camera:N"), std::string::npos);
  EXPECT_NE(errorOf("camera:1x").find("expected camera:N"), std::string::npos);
  EXPECT_NE(errorOf("camera:98").find("camera 98 does not exist"), std::string::npos);
  EXPECT_NE(errorOf("/no/such/video.mp4").find("video file '/no/such/video.mp4' does not exist"),
            std::string::npos);
  EXPECT_NE(errorOf("").find("empty"), std::string::npos);
}
