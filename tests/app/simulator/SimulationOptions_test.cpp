#include "app/simulator/SimulationOptions.hpp"

#include <gtest/gtest.h>

#include "ErrorMessage.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {
std::string checkError(const SimulationOptions& o) {
  return test::errorMessage([&] { o.check(); });
}
}  // namespace

TEST(SimulationOptions, DefaultsAreValidAndEveryPresetIsAccepted) {
  SimulationOptions o;
  EXPECT_EQ(checkError(o), "(no error)");
  EXPECT_EQ(simulationPresets().size(), 6u);
  for (const std::string& p : simulationPresets()) {
    o.preset = p;
    EXPECT_EQ(checkError(o), "(no error)") << p;
  }
}

TEST(SimulationOptions, CheckNamesTheBadField) {
  const std::pair<std::function<void(SimulationOptions&)>, std::string> cases[] = {
      {[](SimulationOptions& o) { o.preset = "spiral"; }, "preset 'spiral'"},
      {[](SimulationOptions& o) { o.frames = 0; }, "frames"},
      {[](SimulationOptions& o) {
         o.size = {0, 480};
       },
       "size"},
      {[](SimulationOptions& o) {
         o.size = {640, 5000};
       },
       "size"},
      {[](SimulationOptions& o) { o.noiseSigma = -1; }, "noiseSigma"},
      {[](SimulationOptions& o) { o.noiseSigma = std::nan(""); }, "noiseSigma"},
      {[](SimulationOptions& o) { o.fovDeg = 170; }, "fovDeg"},
      {[](SimulationOptions& o) { o.fps = 0; }, "fps"},
      {[](SimulationOptions& o) { o.fps = std::numeric_limits<double>::infinity(); }, "fps"},
      {[](SimulationOptions& o) { o.references = 1; }, "references"},
      {[](SimulationOptions& o) { o.referenceBaseline = -0.01; }, "referenceBaseline"},
      {[](SimulationOptions& o) { o.referenceBaseline = std::nan(""); }, "referenceBaseline"},
      {[](SimulationOptions& o) { o.references = kMaxReferences + 1; }, "references"},
      {[](SimulationOptions& o) {
         o.distortion = {-0.3, 0.0, 0.0};
       },
       "distortion"},
      {[](SimulationOptions& o) {
         o.distortion = {-0.3, std::nan(""), 0.0, 0.0};
       },
       "distortion"},
  };
  for (const auto& [mutate, field] : cases) {
    SimulationOptions o;
    mutate(o);
    EXPECT_NE(checkError(o).find(field), std::string::npos) << field << ": " << checkError(o);
  }
}

TEST(SimulationOptions, ReferenceCountDefaultsPerPreset) {
  SimulationOptions o;
  EXPECT_EQ(o.referenceCount(), 2);
  o.preset = "walkaround";
  EXPECT_EQ(o.referenceCount(), 6);
  o.references = 2;
  EXPECT_EQ(o.referenceCount(), 2);
  o.preset = "handheld";
  o.references = 8;
  EXPECT_EQ(o.referenceCount(), 8);
}

TEST(SimulationOptions, ParsesImageSizes) {
  EXPECT_EQ(parseImageSize("640x480"), cv::Size(640, 480));
  EXPECT_EQ(parseImageSize("1x2"), cv::Size(1, 2));
  for (const char* bad : {"", "640", "640x", "x480", "640X480", "640x480x3", "-640x480", "0x480",
                          "640 x 480", "6.4x4.8", "999999x480"})
    EXPECT_FALSE(parseImageSize(bad).has_value()) << bad;
}
