// CameraSource: a camera index that does not exist gives one clear error (no camera is needed).
#include "app/sources/CameraSource.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(CameraSource, MissingCameraIsNamed) {
  ASSERT_FALSE(std::filesystem::exists("/dev/video97"));
  try {
    CameraSource camera(97);
    FAIL() << "camera 97 opened";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "camera 97 does not exist (no /dev/video97)");
  }
  EXPECT_THROW(CameraSource(-1), Error);
}
