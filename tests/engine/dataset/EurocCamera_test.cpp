// EurocCamera: the real EuRoC sensor.yaml format (MH_01's cam0, verbatim), data.csv timestamps
// in ns, the three ways to name the folder, and clear errors for bad layouts.
#include "engine/dataset/EurocCamera.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "DatasetFixtures.hpp"
#include "ErrorMessage.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
namespace fs = std::filesystem;

namespace {

// cam0/sensor.yaml of EuRoC MH_01_easy, as distributed (no %YAML directive).
const char* kMh01Cam0 = R"(# General sensor definitions.
sensor_type: camera
comment: VI-Sensor cam0 (MT9M034)

# Sensor extrinsics wrt. the body-frame.
T_BS:
  cols: 4
  rows: 4
  data: [0.0148655429818, -0.999880929698, 0.00414029679422, -0.0216401454975,
         0.999557249008, 0.0149672133247, 0.025715529948, -0.064676986768,
        -0.0257744366974, 0.00375618835797, 0.999660727178, 0.00981073058949,
         0.0, 0.0, 0.0, 1.0]

# Camera specific definitions.
rate_hz: 20
resolution: [752, 480]
camera_model: pinhole
intrinsics: [458.654, 457.296, 367.215, 248.375] #fu, fv, cu, cv
distortion_model: radial-tangential
distortion_coefficients: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]
)";

fs::path writeMh01Like(const std::string& name) {
  const fs::path dir = test::freshTempDir(name);
  const fs::path cam = dir / "mav0" / "cam0";
  fs::create_directories(cam / "data");
  std::ofstream(cam / "sensor.yaml") << kMh01Cam0;
  std::ofstream csv(cam / "data.csv");
  csv << "#timestamp [ns],filename\r\n";
  for (long long ns : {1403636579763555584LL, 1403636579813555456LL}) {
    cv::imwrite((cam / "data" / (std::to_string(ns) + ".png")).string(),
                cv::Mat(480, 752, CV_8UC1, cv::Scalar(90)));
    csv << ns << ',' << ns << ".png\r\n";
  }
  return dir;
}

std::string errorOf(const fs::path& dir) {
  return test::errorMessage([&] { EurocCamera::open(dir); });
}

}  // namespace

TEST(EurocCamera, ReadsTheRealSensorYamlAndTheFrameList) {
  const fs::path dir = writeMh01Like("EurocCamera_mh01");
  const EurocCamera cam = EurocCamera::open(dir);
  EXPECT_EQ(cam.folder, dir / "mav0" / "cam0");
  EXPECT_EQ(cam.camera.imageSize(), cv::Size(752, 480));
  EXPECT_DOUBLE_EQ(cam.camera.fx(), 458.654);
  EXPECT_DOUBLE_EQ(cam.camera.fy(), 457.296);
  EXPECT_DOUBLE_EQ(cam.camera.cx(), 367.215);
  EXPECT_DOUBLE_EQ(cam.camera.cy(), 248.375);
  ASSERT_EQ(cam.camera.distortion().size(), 4u);
  EXPECT_DOUBLE_EQ(cam.camera.distortion()[0], -0.28340811);
  EXPECT_DOUBLE_EQ(cam.camera.distortion()[3], 1.76187114e-05);
  EXPECT_DOUBLE_EQ(cam.rateHz, 20.0);
  // T_BS: the printed rotation is orthonormal to ~1e-9, the translation is kept exactly.
  EXPECT_NEAR(cam.sensorToBody.rotation()(0, 1), -0.999880929698, 1e-8);
  EXPECT_NEAR(cam.sensorToBody.rotation()(2, 0), -0.0257744366974, 1e-8);
  EXPECT_DOUBLE_EQ(cam.sensorToBody.translation().y(), -0.064676986768);
  ASSERT_EQ(cam.frames.size(), 2u);
  // ns -> s: doubles near 1.4e9 s resolve 2.4e-7 s.
  EXPECT_NEAR(cam.frames[0].timestamp, 1403636579.763555584, 3e-7);
  EXPECT_NEAR(cam.frames[1].timestamp - cam.frames[0].timestamp, 0.049999872, 5e-7);
  EXPECT_EQ(cam.frames[1].file, dir / "mav0" / "cam0" / "data" / "1403636579813555456.png");
  EXPECT_EQ(cam.groundTruthFile(), dir / "mav0" / "state_groundtruth_estimate0" / "data.csv");
  // The same camera folder from mav0, from the folder itself and with a trailing slash.
  EXPECT_EQ(EurocCamera::findFolder(dir / "mav0"), cam.folder);
  EXPECT_EQ(EurocCamera::findFolder(cam.folder), cam.folder);
  EXPECT_EQ(EurocCamera::findFolder(cam.folder.string() + "/"), cam.folder);
}

TEST(EurocCamera, BadLayoutsAreClearErrors) {
  const fs::path empty = test::freshTempDir("EurocCamera_empty");
  EXPECT_NE(errorOf(empty).find("expected DIR/mav0/cam0"), std::string::npos) << errorOf(empty);

  const fs::path dir = writeMh01Like("EurocCamera_bad");
  const fs::path cam = dir / "mav0" / "cam0";
  auto withSensor = [&](const std::string& from, const std::string& to) {
    std::string text = kMh01Cam0;
    text.replace(text.find(from), from.size(), to);
    std::ofstream(cam / "sensor.yaml") << text;
    return errorOf(dir);
  };
  EXPECT_NE(withSensor("367.215, 248.375]", "367.215]").find("'intrinsics' holds 3 numbers"),
            std::string::npos);
  EXPECT_NE(withSensor("camera_model: pinhole", "camera_model: omni").find("not supported"),
            std::string::npos);
  EXPECT_NE(withSensor("radial-tangential", "equidistant").find("only radial-tangential"),
            std::string::npos);
  EXPECT_NE(withSensor("T_BS:", "T_XX:").find("'T_BS'"), std::string::npos);
  EXPECT_NE(withSensor("0.0, 0.0, 0.0, 1.0]", "0.0, 0.0, 1.0, 1.0]").find("not a rigid"),
            std::string::npos);
  EXPECT_NE(withSensor("[752, 480]", "[752]").find("'resolution'"), std::string::npos);
  std::ofstream(cam / "sensor.yaml") << kMh01Cam0;
  std::ofstream(cam / "data.csv") << "#timestamp [ns],filename\n12x,a.png\n";
  EXPECT_NE(errorOf(dir).find("line 2: expected 'timestamp [ns],filename'"), std::string::npos)
      << errorOf(dir);
  std::ofstream(cam / "data.csv") << "1403636579763555584,missing.png\n";
  EXPECT_NE(errorOf(dir).find("missing.png' does not exist"), std::string::npos) << errorOf(dir);
}
