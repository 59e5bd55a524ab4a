// FrameGrabber: file sources lose no frame through a tiny queue, live sources drop the oldest,
// errors reach the consumer after the frames before them, seeking restarts cleanly.
#include "app/sources/FrameGrabber.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

// Frames 0..count-1 (pixel value = index); throws at `failAt` when set.
class ScriptedSource final : public FrameSource {
 public:
  ScriptedSource(int count, bool live, int failAt = -1, bool glThread = false)
      : count_(count), live_(live), failAt_(failAt), glThread_(glThread) {}
  std::optional<Frame> next() override {
    if (next_ == failAt_) throw Error("scripted failure at frame " + std::to_string(next_));
    if (next_ >= count_) return std::nullopt;
    reads.fetch_add(1);
    readerThread = std::this_thread::get_id();
    const int k = next_++;
    return Frame{cv::Mat(1, 1, CV_8UC3, cv::Scalar::all(k % 256)), k, k / 30.0};
  }
  std::optional<int> frameCount() const override { return count_; }
  double fps() const override { return 30.0; }
  bool seekable() const override { return true; }
  void seek(int index) override { next_ = index; }
  bool isLive() const override { return live_; }
  bool needsGlThread() const override { return glThread_; }
  std::string description() const override { return "scripted"; }

  std::atomic<int> reads{0};
  std::thread::id readerThread;

 private:
  int count_, next_ = 0;
  bool live_;
  int failAt_;
  bool glThread_;
};

}  // namespace

TEST(FrameGrabber, FileSourceDeliversEveryFrameInOrder) {
  FrameGrabber grabber(std::make_unique<ScriptedSource>(200, false), 2);
  for (int k = 0; k < 200; ++k) {
    const auto frame = grabber.next();
    ASSERT_TRUE(frame) << k;
    ASSERT_EQ(frame->index, k);
    if (k % 50 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_FALSE(grabber.next());
  EXPECT_EQ(grabber.droppedFrames(), 0u);
}

TEST(FrameGrabber, LiveSourceDropsTheOldestFrames) {
  auto source = std::make_unique<ScriptedSource>(100, true);
  ScriptedSource* raw = source.get();
  FrameGrabber grabber(std::move(source), 3);
  // Let the reader run ahead: all 100 frames are read while nobody consumes.
  for (int i = 0; i < 200 && raw->reads.load() < 100; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_EQ(raw->reads.load(), 100);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // the last push and the end
  std::vector<int> got;
  while (const auto frame = grabber.next()) got.push_back(frame->index);
  EXPECT_EQ(got, (std::vector<int>{97, 98, 99}));  // the newest `capacity` frames
  EXPECT_EQ(grabber.droppedFrames(), 97u);
}

TEST(FrameGrabber, ErrorIsRethrownAfterTheFramesBeforeIt) {
  FrameGrabber grabber(std::make_unique<ScriptedSource>(10, false, 4), 8);
  for (int k = 0; k < 4; ++k) ASSERT_EQ(grabber.next()->index, k);
  try {
    grabber.next();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "scripted failure at frame 4");
  }
}

TEST(FrameGrabber, SeekRestartsFromTheRequestedFrame) {
  FrameGrabber grabber(std::make_unique<ScriptedSource>(50, false), 4);
  ASSERT_EQ(grabber.next()->index, 0);
  grabber.seek(40);
  for (int k = 40; k < 50; ++k) ASSERT_EQ(grabber.next()->index, k);
  EXPECT_FALSE(grabber.next());
  grabber.seek(3);
  EXPECT_EQ(grabber.next()->index, 3);
}

TEST(FrameGrabber, GlThreadSourcesAreReadOnTheCallingThread) {
  auto source = std::make_unique<ScriptedSource>(3, false, -1, true);
  ScriptedSource* raw = source.get();
  FrameGrabber grabber(std::move(source));
  EXPECT_EQ(raw->reads.load(), 0);  // nothing read ahead
  ASSERT_EQ(grabber.next()->index, 0);
  EXPECT_EQ(raw->readerThread, std::this_thread::get_id());
}

TEST(FrameGrabber, DestructionStopsABlockedReader) {
  // The reader of a long file source blocks on the full queue: it reads no further ahead than the
  // queue and the frame in its hand, and destruction stops it (a hang here ends in the test's
  // timeout; nothing is timed).
  auto source = std::make_unique<ScriptedSource>(1000000, false);
  const ScriptedSource* raw = source.get();
  int readAhead = 0;
  {
    FrameGrabber grabber(std::move(source), 2);
    ASSERT_EQ(grabber.next()->index, 0);
    // Give the reader the chance to run ahead as far as it would (1 taken + 2 queued + 1).
    for (int i = 0; i < 200 && raw->reads.load() < 4; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    readAhead = raw->reads.load();
  }
  EXPECT_LE(readAhead, 4);
  EXPECT_GE(readAhead, 1);
}

namespace {

// A live camera unplugged after frame 2: next() throws until reconnect() has been tried
// `refusals` times; then frames continue from index 3.
class UnpluggedCamera final : public FrameSource {
 public:
  explicit UnpluggedCamera(int refusals) : refusals_(refusals) {}
  std::optional<Frame> next() override {
    if (unplugged_) throw Error("camera 9 stopped delivering frames");
    if (next_ == 3 && !wasUnplugged_) {
      unplugged_ = wasUnplugged_ = true;
      throw Error("camera 9 stopped delivering frames");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));  // a camera's frame interval
    const int k = next_++;
    return Frame{cv::Mat(1, 1, CV_8UC3, cv::Scalar::all(k)), k, k / 30.0};
  }
  bool reconnect() override {
    attempts.fetch_add(1);
    if (attempts.load() <= refusals_) return false;
    unplugged_ = false;
    return true;
  }
  std::optional<int> frameCount() const override { return std::nullopt; }
  double fps() const override { return 30.0; }
  bool isLive() const override { return true; }
  std::string description() const override { return "camera 9 (live)"; }
  std::atomic<int> attempts{0};

 private:
  int refusals_, next_ = 0;
  bool unplugged_ = false, wasUnplugged_ = false;
};

template <class Condition>
bool eventually(Condition condition) {
  for (int i = 0; i < 500; ++i) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

}  // namespace

TEST(FrameGrabber, AnUnpluggedCameraIsReportedAndPickedUpAgainWhenItReturns) {
  auto camera = std::make_unique<UnpluggedCamera>(2);
  UnpluggedCamera& raw = *camera;
  // Capacity 8 > 3 frames: nothing is dropped before the unplugging.
  FrameGrabber grabber(std::move(camera), 8, std::chrono::milliseconds(20));
  for (int k = 0; k < 3; ++k) {
    const std::optional<Frame> f = grabber.next();
    ASSERT_TRUE(f);
    EXPECT_EQ(f->index, k);
  }
  // While away: the reason is reported, next() does not block and gives nothing.
  ASSERT_TRUE(eventually([&] { return grabber.disconnected().has_value(); }));
  EXPECT_NE(grabber.disconnected()->find("stopped delivering"), std::string::npos);
  EXPECT_TRUE(grabber.frameReady());
  // Back after two refused reconnections: frames continue, the state clears.
  ASSERT_TRUE(eventually([&] { return !grabber.disconnected().has_value(); }));
  EXPECT_EQ(raw.attempts.load(), 3);
  std::optional<Frame> f;
  ASSERT_TRUE(eventually([&] { return (f = grabber.next()).has_value(); }));
  EXPECT_EQ(f->index, 3);
}
