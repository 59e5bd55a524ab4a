#include "engine/calibration/CalibrationInput.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

TEST(CalibrationInput, ReadsFolderGlobAndVideo) {
  const auto dir = test::freshTempDir("CalibrationInput_Sources");
  for (int i = 0; i < 3; ++i)
    // (std::string("b") + ...: GCC 12's -Wrestrict misfires on const char* + std::string&&.)
    cv::imwrite((dir / (std::string("b") + std::to_string(i) + ".png")).string(),
                cv::Mat(48, 64, CV_8UC1, cv::Scalar(i * 50)));
  cv::imwrite((dir / "c0.png").string(), cv::Mat(48, 64, CV_8UC1, cv::Scalar(9)));
  std::ofstream(dir / "notes.txt") << "not an image\n";

  CalibrationInput folder(dir.string());
  EXPECT_EQ(folder.size(), 4u);
  cv::Mat img;
  std::string label;
  ASSERT_TRUE(folder.next(img, label));
  EXPECT_EQ(label, "b0.png");
  EXPECT_EQ(img.size(), cv::Size(64, 48));

  CalibrationInput glob((dir / "b*.png").string());
  EXPECT_EQ(glob.size(), 3u);

  const auto video = dir / "v.avi";
  {
    cv::VideoWriter w(video.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10,
                      cv::Size(64, 48));
    ASSERT_TRUE(w.isOpened());
    for (int i = 0; i < 20; ++i) w.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar(i * 10, 0, 0)));
  }
  CalibrationInput sampled(video.string(), 5);  // 20 frames sampled down to every 4th
  EXPECT_TRUE(sampled.isVideo());
  std::vector<std::string> labels;
  while (sampled.next(img, label)) labels.push_back(label);
  ASSERT_EQ(labels.size(), 5u);
  EXPECT_EQ(labels[1], "frame 4");
}

TEST(CalibrationInput, ExplainsUnusableSources) {
  const auto dir = test::freshTempDir("CalibrationInput_Bad");
  EXPECT_THROW(CalibrationInput((dir / "missing").string()), Error);
  EXPECT_THROW(CalibrationInput(dir.string()), Error);  // empty folder
  EXPECT_THROW(CalibrationInput((dir / "*.png").string()), Error);
  std::ofstream(dir / "junk.mp4") << "not a video";
  EXPECT_THROW(CalibrationInput((dir / "junk.mp4").string()), Error);
  std::ofstream(dir / "broken.png") << "not a png";
  CalibrationInput broken((dir / "broken.png").string());
  cv::Mat img;
  std::string label;
  EXPECT_THROW(broken.next(img, label), Error);
}
