// FragmentedMp4Writer: every frame comes back decoded and close to what was written, the file is
// fragmented (moof boxes; an unfinished file still plays its complete fragments), odd sizes are
// padded, and the C heap does not grow with the number of frames written.
#include "app/viewer/FragmentedMp4Writer.hpp"

#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdint>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;
namespace fs = std::filesystem;

namespace {

// A smooth moving pattern (what a quantiser-3 MPEG-4 encoder reproduces closely).
cv::Mat patternFrame(cv::Size size, int k) {
  cv::Mat image(size, CV_8UC3);
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x)
      image.at<cv::Vec3b>(y, x) = {static_cast<std::uint8_t>((x + 3 * k) % 256),
                                   static_cast<std::uint8_t>((y * 2) % 256),
                                   static_cast<std::uint8_t>(128 + 60 * ((x / 16 + y / 16) % 2))};
  return image;
}

std::vector<cv::Mat> decodeAll(const fs::path& file) {
  cv::VideoCapture capture(file.string(), cv::CAP_FFMPEG);
  std::vector<cv::Mat> frames;
  for (cv::Mat image; capture.read(image);) frames.push_back(image.clone());
  return frames;
}

// Top-level MP4 box types in file order.
std::vector<std::string> topLevelBoxes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::vector<std::string> boxes;
  for (;;) {
    unsigned char header[8];
    if (!in.read(reinterpret_cast<char*>(header), 8)) break;
    std::uint64_t size =
        (std::uint64_t{header[0]} << 24) | (header[1] << 16) | (header[2] << 8) | header[3];
    boxes.emplace_back(reinterpret_cast<char*>(header + 4), 4);
    if (size < 8) break;  // 0 (to the end) and 1 (64-bit size) do not occur in these files
    in.seekg(static_cast<std::streamoff>(size - 8), std::ios::cur);
  }
  return boxes;
}

double heapInUseBytes() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd);
}

}  // namespace

TEST(FragmentedMp4Writer, FramesComeBackFromAFragmentedFile) {
  const fs::path file = test::freshTempDir("FragmentedMp4Writer_RoundTrip") / "clip.mp4";
  const cv::Size size(160, 120);
  {
    FragmentedMp4Writer writer(file, 30.0, size);
    for (int k = 0; k < 75; ++k) writer.write(patternFrame(size, k));
    writer.finish();
  }
  const std::vector<cv::Mat> decoded = decodeAll(file);
  ASSERT_EQ(decoded.size(), 75u);
  for (int k : {0, 31, 74}) {
    ASSERT_EQ(decoded[k].size(), size);
    // Quantiser 3 on this smooth pattern: PSNR well above 30 dB (measured 36-40 dB); a wrong
    // frame order or colour swap gives < 20 dB.
    EXPECT_GT(cv::PSNR(decoded[k], patternFrame(size, k)), 30.0) << "frame " << k;
  }
  cv::VideoCapture capture(file.string(), cv::CAP_FFMPEG);
  EXPECT_EQ(capture.get(cv::CAP_PROP_FRAME_COUNT), 75.0);
  EXPECT_NEAR(capture.get(cv::CAP_PROP_FPS), 30.0, 1e-6);
  const std::vector<std::string> boxes = topLevelBoxes(file);
  ASSERT_GE(boxes.size(), 4u);
  EXPECT_EQ(boxes[0], "ftyp");
  EXPECT_EQ(boxes[1], "moov");  // up front: no index held until the end
  // A fragment per key frame, one per second: 75 frames at 30 fr/s -> 3 fragments.
  EXPECT_EQ(std::count(boxes.begin(), boxes.end(), "moof"), 3);
}

TEST(FragmentedMp4Writer, AnUnfinishedFileKeepsItsCompleteFragments) {
  const fs::path file = test::freshTempDir("FragmentedMp4Writer_Unfinished") / "cut.mp4";
  const cv::Size size(96, 64);
  {
    FragmentedMp4Writer writer(file, 25.0, size);
    for (int k = 0; k < 60; ++k) writer.write(patternFrame(size, k));
    // destroyed without finish(), as when a process dies mid-recording
  }
  // Fragments of 25 frames each are flushed at the next key frame: 50 frames are on disk.
  EXPECT_GE(decodeAll(file).size(), 50u);
}

TEST(FragmentedMp4Writer, OddSizesArePaddedAndDecodeAtTheEncodedSize) {
  const fs::path file = test::freshTempDir("FragmentedMp4Writer_Odd") / "odd.mp4";
  {
    FragmentedMp4Writer writer(file, 30.0, {161, 121});
    for (int k = 0; k < 5; ++k) writer.write(patternFrame({161, 121}, k));
    writer.finish();
  }
  const std::vector<cv::Mat> decoded = decodeAll(file);
  ASSERT_EQ(decoded.size(), 5u);
  EXPECT_EQ(decoded[0].size(), cv::Size(162, 122));
  EXPECT_GT(cv::PSNR(decoded[2](cv::Rect(0, 0, 161, 121)), patternFrame({161, 121}, 2)), 30.0);
}

TEST(FragmentedMp4Writer, MemoryDoesNotGrowWithTheFrameCount) {
  const fs::path file = test::freshTempDir("FragmentedMp4Writer_Memory") / "long.mp4";
  const cv::Size size(64, 48);
  const cv::Mat frame = patternFrame(size, 0);
  FragmentedMp4Writer writer(file, 30.0, size);
  for (int k = 0; k < 300; ++k) writer.write(frame);
  const double before = heapInUseBytes();
  for (int k = 0; k < 6000; ++k) writer.write(frame);
  const double grown = heapInUseBytes() - before;
  writer.finish();
  // A plain MP4 keeps ~64 bytes of index per frame until the end: 6000 frames -> ~375 kB. Here
  // only a ~40-byte record per fragment (200 fragments -> 8 kB) remains; 64 kB leaves room for
  // allocator noise and still fails for a per-frame index.
  EXPECT_LT(grown, 64.0 * 1024) << grown << " bytes";
}

TEST(FragmentedMp4Writer, BadArgumentsAndFramesAreClearErrors) {
  const fs::path dir = test::freshTempDir("FragmentedMp4Writer_Errors");
  EXPECT_THROW(FragmentedMp4Writer(dir / "a.mp4", 30.0, {0, 10}), Error);
  EXPECT_THROW(FragmentedMp4Writer(dir / "b.mp4", 0.0, {16, 16}), Error);
  EXPECT_THROW(FragmentedMp4Writer(dir / "missing" / "c.mp4", 30.0, {16, 16}), Error);
  FragmentedMp4Writer writer(dir / "d.mp4", 30.0, {32, 32});
  EXPECT_THROW(writer.write(cv::Mat(16, 16, CV_8UC3)), Error);
  EXPECT_THROW(writer.write(cv::Mat(32, 32, CV_8UC1)), Error);
  writer.write(cv::Mat(32, 32, CV_8UC3, cv::Scalar(1, 2, 3)));
  writer.finish();
  EXPECT_THROW(writer.write(cv::Mat(32, 32, CV_8UC3)), Error);
}
