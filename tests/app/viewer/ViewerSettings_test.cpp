// ViewerSettings: one YAML file for the viewer that every command-line tool's --params accepts.
#include "app/viewer/ViewerSettings.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(ViewerSettings, RoundTripsAndIsATrackerParamsFile) {
  const auto dir = test::freshTempDir("ViewerSettings_RoundTrip");
  ViewerSettings s;
  s.tracker.mode = TrackingMode::Homography;
  s.tracker.pose.alpha = 2.5;
  s.tracker.ransac.maxIterations = 123;
  s.overlay.size = 0.3;
  s.overlay.showLabels = false;
  s.save(dir / "p.yml");
  const ViewerSettings r = ViewerSettings::load(dir / "p.yml");
  EXPECT_EQ(r.tracker.mode, TrackingMode::Homography);
  EXPECT_DOUBLE_EQ(r.tracker.pose.alpha, 2.5);
  EXPECT_EQ(r.tracker.ransac.maxIterations, 123);
  EXPECT_DOUBLE_EQ(r.overlay.size, 0.3);
  EXPECT_FALSE(r.overlay.showLabels);
  // The command-line tools read the same file (the overlay section is ignored there).
  EXPECT_EQ(TrackerParams::load(dir / "p.yml").ransac.maxIterations, 123);
}

TEST(ViewerSettings, PlainTrackerParamsFileLoadsWithDefaultOverlay) {
  const auto dir = test::freshTempDir("ViewerSettings_Plain");
  TrackerParams p;
  p.correlation.minScore = 0.9;
  p.save(dir / "t.yml");
  const ViewerSettings r = ViewerSettings::load(dir / "t.yml");
  EXPECT_DOUBLE_EQ(r.tracker.correlation.minScore, 0.9);
  EXPECT_DOUBLE_EQ(r.overlay.size, OverlaySettings{}.size);
}

TEST(ViewerSettings, BadOverlayEntryNamesFileAndKey) {
  const auto dir = test::freshTempDir("ViewerSettings_Bad");
  std::ofstream(dir / "b.yml") << "%YAML:1.0\n---\noverlay:\n  line_width_px: .nan\n";
  try {
    ViewerSettings::load(dir / "b.yml");
    FAIL();
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("b.yml"), std::string::npos) << m;
    EXPECT_NE(m.find("line_width_px"), std::string::npos) << m;
  }
}

TEST(ViewerSettings, UnknownOverlayKeysNameTheNearestAndTheYamlLineIsOptional) {
  const auto dir = test::freshTempDir("ViewerSettings_Strict");
  std::ofstream(dir / "s.yml") << "overlay:\n  line_width: 3\n";
  try {
    ViewerSettings::load(dir / "s.yml");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "overlay.line_width: unknown key — did you mean overlay.line_width_px?"),
              std::string::npos)
        << e.what();
  }
  std::ofstream(dir / "t.yml") << "overlay:\n  size: 0.4\nransac: {seed: 4}\n";
  const ViewerSettings s = ViewerSettings::load(dir / "t.yml");
  EXPECT_DOUBLE_EQ(s.overlay.size, 0.4);
  EXPECT_EQ(s.tracker.ransac.seed, 4);
}
