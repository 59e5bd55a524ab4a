// OverlayCompositor over a simulator frame with its true pose: the cube's vertex dots (distinct
// colours) are centred within 0.5 px of K[R|t]X; debug layers and labels change the image only
// where asked; a frame of the wrong size is refused.
#include "app/viewer/OverlayCompositor.hpp"

#include <gtest/gtest.h>

#include "app/simulator/SceneSimulator.hpp"
#include "engine/core/Error.hpp"
#include "render/context/GlContext.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

class OverlayCompositorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = render::createHeadlessContext();
    SimulationOptions options;
    options.preset = "handheld";
    options.frames = 10;
    options.size = {640, 480};
    sim_ = std::make_unique<SceneSimulator>(options);
  }
  std::unique_ptr<render::GlContext> context_;
  std::unique_ptr<SceneSimulator> sim_;
};

// Centroid of the pixels within `radius` of `centre` that the overlay changed to (nearly)
// `colour`; nullopt when none.
std::optional<cv::Point2d> dotCentroid(const cv::Mat& before, const cv::Mat& after,
                                       const cv::Point2d& centre, double radius,
                                       const cv::Scalar& colour) {
  double sx = 0, sy = 0, n = 0;
  for (int y = std::max(0, cvFloor(centre.y - radius)); y <= cvCeil(centre.y + radius); ++y)
    for (int x = std::max(0, cvFloor(centre.x - radius)); x <= cvCeil(centre.x + radius); ++x) {
      if (y >= after.rows || x >= after.cols) continue;
      if (std::hypot(x - centre.x, y - centre.y) > radius) continue;
      const cv::Vec3b a = after.at<cv::Vec3b>(y, x), b = before.at<cv::Vec3b>(y, x);
      if (a == b) continue;
      bool match = true;
      for (int c = 0; c < 3; ++c) match &= std::abs(a[c] - colour[c]) <= 40;
      if (!match) continue;
      sx += x;
      sy += y;
      n += 1;
    }
  if (n == 0) return std::nullopt;
  return cv::Point2d(sx / n, sy / n);
}

// Composites the cube at the true pose of frames 0, 5 and 9 and checks each isolated vertex dot
// against the camera's projection through its lens (projectDistorted: the pinhole projection
// when there is no distortion). Returns the number of dots measured.
int checkVertexDots(SceneSimulator& sim) {
  OverlayCompositor compositor;
  OverlaySettings settings;
  settings.size = 0.12;
  settings.offset = Eigen::Vector3d(0.02, -0.01, 0.0);
  settings.showLabels = false;
  render::WireframeCubeStyle style;  // the compositor's cube: same size and placement
  style.edgeLength = settings.size;
  style.modelToWorld = settings.cubeModelToWorld();
  const auto vertices = render::WireframeCube::worldVertices(style);
  const auto& colours = render::WireframeCube::vertexColoursBgr();
  const double dotRadius = style.dotRadiusPx;
  int measured = 0;
  for (int k : {0, 5, 9}) {
    const cv::Mat frame = sim.renderFrame(k);
    TrackingResult result;
    result.worldToCamera = sim.framePose(k);
    const cv::Mat out = compositor.composite(frame, sim.camera(), result, settings);
    EXPECT_EQ(out.size(), frame.size());
    std::vector<Eigen::Vector2d> projected;
    for (const auto& X : vertices)
      projected.push_back(sim.camera().projectDistorted(*result.worldToCamera * X));
    for (int i = 0; i < 8; ++i) {
      // A dot partly covered by another vertex's dot has a biased centroid: skip those.
      bool isolated = true;
      for (int j = 0; j < 8; ++j)
        if (j != i && (projected[i] - projected[j]).norm() < 2 * dotRadius + 2) isolated = false;
      const cv::Point2d centre(projected[i].x(), projected[i].y());
      if (!isolated || centre.x < dotRadius || centre.y < dotRadius ||
          centre.x > frame.cols - 1 - dotRadius || centre.y > frame.rows - 1 - dotRadius)
        continue;
      const auto c = dotCentroid(frame, out, centre, dotRadius + 2, colours[i]);
      EXPECT_TRUE(c) << "frame " << k << " vertex " << i << " not drawn";
      if (!c) continue;
      // 0.5 px: the bound. A rasterised 32-gon of radius 5 px has its pixel centroid
      // within ~0.1 px of the true centre, so a half-pixel convention error would fail.
      EXPECT_LT(cv::norm(*c - centre), 0.5) << "frame " << k << " vertex " << i;
      ++measured;
    }
  }
  return measured;
}

}  // namespace

TEST_F(OverlayCompositorTest, CubeVertexDotsLandOnTheTrueProjection) {
  EXPECT_GE(checkVertexDots(*sim_), 12);  // most vertices are visible and isolated in these views
}

// Through a k1 = -0.3 lens the compositor bends the overlay with the camera's distortion: the
// dots land where the lens put the video (the pinhole projection is off by pixels here).
TEST_F(OverlayCompositorTest, CubeVertexDotsFollowTheLensDistortion) {
  SimulationOptions options;
  options.preset = "handheld";
  options.frames = 10;
  options.size = {640, 480};
  options.fovDeg = 50.0;
  options.distortion = {-0.3, 0.0, 0.0, 0.0};
  SceneSimulator distorted(options);
  EXPECT_GE(checkVertexDots(distorted), 12);
}

TEST_F(OverlayCompositorTest, LostFramesShowTheVideoOnly) {
  OverlayCompositor compositor;
  OverlaySettings settings;
  settings.showLabels = false;
  const cv::Mat frame = sim_->renderFrame(0);
  TrackingResult lost;
  lost.status = "lost";
  const cv::Mat out = compositor.composite(frame, sim_->camera(), lost, settings);
  // The background is drawn pixel-exact when the viewport has the frame's size.
  EXPECT_EQ(cv::norm(out, frame, cv::NORM_INF), 0.0);
  const cv::Mat labelled = compositor.composite(
      frame, sim_->camera(), lost,
      [] {
        OverlaySettings s;
        return s;
      }(),
      "frame 0 lost");
  EXPECT_GT(cv::norm(labelled, frame, cv::NORM_L1), 0.0);
}

// An uncertain pose (above pose.max_predicted_error_px) is not drawn as if exact: no vertex dot
// and no edge of the cube's colour, but the thin grey cube still changes the image.
TEST_F(OverlayCompositorTest, AnUncertainPoseDrawsTheCubeDimmed) {
  OverlayCompositor compositor;
  OverlaySettings settings;
  settings.showLabels = false;
  const cv::Mat frame = sim_->renderFrame(0);
  TrackingResult exact;
  exact.worldToCamera = sim_->framePose(0);
  TrackingResult uncertain = exact;
  uncertain.uncertain = true;
  const cv::Mat drawn = compositor.composite(frame, sim_->camera(), exact, settings);
  const cv::Mat dimmed = compositor.composite(frame, sim_->camera(), uncertain, settings);
  // Pixels (changed from the frame) of the cube's edge colour or of a vertex colour.
  const auto coloured = [&](const cv::Mat& out) {
    std::vector<cv::Scalar> colours = {render::WireframeCubeStyle{}.colourBgr};
    for (const cv::Scalar& c : render::WireframeCube::vertexColoursBgr()) colours.push_back(c);
    int n = 0;
    for (int y = 0; y < out.rows; ++y)
      for (int x = 0; x < out.cols; ++x) {
        const cv::Vec3b a = out.at<cv::Vec3b>(y, x);
        if (a == frame.at<cv::Vec3b>(y, x)) continue;
        for (const cv::Scalar& c : colours) {
          bool match = true;
          for (int k = 0; k < 3; ++k) match &= std::abs(a[k] - c[k]) <= 30;
          if (match) {
            ++n;
            break;
          }
        }
      }
    return n;
  };
  EXPECT_GT(coloured(drawn), 500);
  EXPECT_LT(coloured(dimmed), 20);
  EXPECT_GT(cv::norm(dimmed, frame, cv::NORM_L1), 0.0);
  EXPECT_LT(cv::norm(dimmed, frame, cv::NORM_L1), 0.5 * cv::norm(drawn, frame, cv::NORM_L1));
}

TEST_F(OverlayCompositorTest, DebugLayersFollowTheirSwitches) {
  OverlayCompositor compositor;
  const cv::Mat frame = sim_->renderFrame(0);
  TrackingResult result;
  result.status = "tracking";
  result.debug.corners = {{100, 100}};
  result.debug.matches = {{{200, 200}, {260, 220}}};
  result.debug.epipolarLines = {cv::Vec3d(0, 1, -400)};  // the row y = 400
  OverlaySettings off;
  off.showCorners = off.showMatches = off.showEpipolarLines = off.showLabels = false;
  EXPECT_EQ(cv::norm(compositor.composite(frame, sim_->camera(), result, off), frame, cv::NORM_INF),
            0.0);
  OverlaySettings on = off;
  on.showCorners = on.showMatches = on.showEpipolarLines = true;
  const cv::Mat out = compositor.composite(frame, sim_->camera(), result, on);
  auto changed = [&](int x, int y) { return out.at<cv::Vec3b>(y, x) != frame.at<cv::Vec3b>(y, x); };
  EXPECT_TRUE(changed(100, 100));  // corner dot
  EXPECT_TRUE(changed(230, 210));  // middle of the match segment
  EXPECT_TRUE(changed(10, 400));   // epipolar line across the image
  EXPECT_FALSE(changed(500, 50));  // elsewhere untouched
}

TEST_F(OverlayCompositorTest, FrameOfTheWrongSizeIsRefused) {
  OverlayCompositor compositor;
  TrackingResult result;
  EXPECT_THROW(compositor.composite(cv::Mat(100, 100, CV_8UC3, cv::Scalar::all(0)), sim_->camera(),
                                    result, OverlaySettings{}),
               Error);
}
