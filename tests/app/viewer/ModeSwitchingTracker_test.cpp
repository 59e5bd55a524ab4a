#include "app/viewer/ModeSwitchingTracker.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"

namespace reftrack::app {
namespace {

// A tracker that reports its own name as the status, and counts the parameters it received.
class NamedTracker : public FrameTracker {
 public:
  explicit NamedTracker(std::string name) : name_(std::move(name)) {}
  TrackingResult process(const cv::Mat&, int, double) override {
    TrackingResult r;
    r.status = name_;
    return r;
  }
  void applyParams(const TrackerParams&) override { ++applied; }
  std::string name() const override { return name_; }
  int applied = 0;

 private:
  std::string name_;
};

TEST(ModeSwitchingTracker, TheModeSwitchSelectsTheTracker) {
  auto sixDof = std::make_unique<NamedTracker>("6dof");
  auto homography = std::make_unique<NamedTracker>("homography");
  NamedTracker* h = homography.get();
  ModeSwitchingTracker t(std::move(sixDof), std::move(homography), TrackingMode::SixDof);
  const cv::Mat frame(10, 10, CV_8UC3);
  EXPECT_EQ(t.process(frame, 0, 0.0).status, "6dof");
  TrackerParams p;
  p.mode = TrackingMode::Homography;
  t.applyParams(p);
  EXPECT_EQ(h->applied, 1);
  EXPECT_EQ(t.process(frame, 1, 0.1).status, "homography");
  EXPECT_EQ(t.name(), "homography");
}

TEST(ModeSwitchingTracker, AModeWithoutItsInputIsAClearErrorAndChangesNothing) {
  ModeSwitchingTracker t(std::make_unique<NamedTracker>("6dof"), nullptr, TrackingMode::Homography);
  EXPECT_EQ(t.name(), "6dof");  // the only tracker available
  TrackerParams p;
  p.mode = TrackingMode::Homography;
  try {
    t.applyParams(p);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--reference"), std::string::npos) << e.what();
  }
  EXPECT_EQ(t.process(cv::Mat(10, 10, CV_8UC3), 0, 0.0).status, "6dof");
  EXPECT_THROW(ModeSwitchingTracker(nullptr, nullptr, TrackingMode::SixDof), Error);
}

}  // namespace
}  // namespace reftrack::app
