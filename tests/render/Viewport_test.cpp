#include "render/Viewport.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "render/RenderTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::render;

TEST(Viewport, FitImageLetterboxesAndPillarboxes) {
  EXPECT_EQ(fitImage({640, 480}, {640, 480}), (Viewport{0, 0, 640, 480}));
  // Wide window: bars left and right.
  EXPECT_EQ(fitImage({640, 480}, {1280, 720}), (Viewport{160, 0, 960, 720}));
  // Tall window: bars top and bottom.
  EXPECT_EQ(fitImage({640, 480}, {800, 1000}), (Viewport{0, 200, 800, 600}));
  EXPECT_THROW(fitImage({0, 480}, {800, 600}), Error);
  EXPECT_THROW(fitImage({640, 480}, {800, 0}), Error);
}

using ViewportTest = test::HeadlessGlTest;

TEST_F(ViewportTest, AppliedViewportReadsBack) {
  applyViewport({3, 4, 50, 60});
  EXPECT_EQ(currentViewport(), (Viewport{3, 4, 50, 60}));
}
