// FrameSource's defaults: not seekable, not live, read on any thread; seek() refuses by name.
#include "app/sources/FrameSource.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

class CountingSource final : public FrameSource {
 public:
  std::optional<Frame> next() override {
    if (n_ >= 2) return std::nullopt;
    return Frame{cv::Mat(2, 2, CV_8UC3), n_++, 0.0};
  }
  std::optional<int> frameCount() const override { return 2; }
  double fps() const override { return 10.0; }
  std::string description() const override { return "counting source"; }

 private:
  int n_ = 0;
};

}  // namespace

TEST(FrameSource, DefaultsAreANonSeekableFileLikeSource) {
  CountingSource source;
  EXPECT_FALSE(source.seekable());
  EXPECT_FALSE(source.isLive());
  EXPECT_FALSE(source.needsGlThread());
  try {
    source.seek(1);
    FAIL() << "seek should throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("counting source cannot seek"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(source.next()->index, 0);
  EXPECT_EQ(source.next()->index, 1);
  EXPECT_FALSE(source.next());
}
