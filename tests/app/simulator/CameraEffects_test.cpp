#include "app/simulator/CameraEffects.hpp"

#include <gtest/gtest.h>

#include "ErrorMessage.hpp"
#include "engine/config/ConfigFile.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(CameraEffects, NoneIsAllOffAndWebcamSwitchesEveryEffectOn) {
  EXPECT_FALSE(cameraEffectsFor("none", {640, 480}).any());
  EXPECT_FALSE(CameraEffects{}.any());
  const CameraEffects w = cameraEffectsFor("webcam", {640, 480});
  EXPECT_TRUE(w.photos);
  EXPECT_GT(w.exposureMs, 0.0);
  EXPECT_GT(w.readoutMs, 0.0);
  EXPECT_GT(w.gainStep, 0.0);
  EXPECT_GT(w.flickerAmplitude, 0.0);
  EXPECT_GT(w.vignetting, 0.0);
  EXPECT_TRUE(w.poissonNoise);
  EXPECT_GT(w.defocusRadiusPx, 0.0);
  EXPECT_EQ(w.codec, "h264");
  // Defocus is given at 640 px wide and scales with the width.
  EXPECT_DOUBLE_EQ(cameraEffectsFor("defocus", {1280, 720}).defocusRadiusPx,
                   2.0 * w.defocusRadiusPx);
}

TEST(CameraEffects, EachNameSwitchesOnOneEffect) {
  for (const std::string& name : cameraEffectNames()) {
    const CameraEffects e = cameraEffectsFor(name, {640, 480});
    EXPECT_TRUE(e.any()) << name;
    EXPECT_FALSE(e.key().empty()) << name;
  }
  const CameraEffects two = cameraEffectsFor("blur,rolling-shutter", {640, 480});
  EXPECT_GT(two.exposureMs, 0.0);
  EXPECT_GT(two.readoutMs, 0.0);
  EXPECT_EQ(two.vignetting, 0.0);
  EXPECT_NE(cameraEffectsFor("blur", {640, 480}).key(),
            cameraEffectsFor("flicker", {640, 480}).key());
}

TEST(CameraEffects, UnknownNamesAndBadValuesAreNamed) {
  try {
    cameraEffectsFor("blur,sparkle", {640, 480});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("sparkle"), std::string::npos);
  }
  CameraEffects e;
  e.vignetting = 2.0;
  try {
    e.check();
    FAIL() << "no error";
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("effects.vignetting"), std::string::npos);
  }
  e = {};
  e.codec = "vp9";
  EXPECT_THROW(e.check(), Error);
}

TEST(CameraEffects, RoundTripsThroughFileStorage) {
  CameraEffects e = cameraEffectsFor("webcam", {640, 480});
  e.jpegQuality = 60;
  cv::FileStorage out(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  out << "effects"
      << "{";
  e.write(out);
  out << "}";
  CameraEffects back;
  back.read(readConfigText(out.releaseAndGetString(), "effects file")["effects"]);
  EXPECT_EQ(back.key(), e.key());
  EXPECT_EQ(back.jpegQuality, 60);
  EXPECT_EQ(back.codec, "h264");
}

TEST(CameraEffects, ReadRefusesAnUnknownKeyNamingTheNearestKnownOne) {
  const YamlNode in = readConfigText("%YAML:1.0\neffects: { vignette: 0.2 }\n", "effects file");
  CameraEffects e;
  EXPECT_EQ(test::errorMessage([&] { e.read(in["effects"]); }),
            "line 2: effects.vignette: unknown key — did you mean effects.vignetting?");
}
