#include "app/research/sixdof/RealClipSuiteBenchmark.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"
#include "engine/geometry/TumTrajectory.hpp"

namespace reftrack::app {
namespace {

namespace fs = std::filesystem;

// A data root holding clip folder `a` (six 64x48 frames, its camera and ground truth), and a
// suite of clips `a` and `b` (whose folder is absent).
struct DataRoot {
  fs::path root;
  RealClipSuite suite;
  explicit DataRoot(const std::string& name) {
    root = test::freshTempDir(name) / "data";
    fs::create_directories(root / "a" / "frames");
    for (int k = 0; k < 6; ++k)
      cv::imwrite((root / "a" / "frames" / ("00000" + std::to_string(k) + ".png")).string(),
                  cv::Mat(48, 64, CV_8UC3, cv::Scalar(k, k, k)));
    Eigen::Matrix3d K;
    K << 100, 0, 31.5, 0, 100, 23.5, 0, 0, 1;
    PinholeCamera(K, cv::Size(64, 48)).save(root / "a" / "camera.yml");
    TumTrajectory gt;
    for (int k = 0; k < 6; ++k)
      gt.poses.push_back(
          {k / 30.0, RigidPose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.01 * k, 0, 1))});
    gt.save(root / "a" / "groundtruth.txt");
    const std::string clip =
        "    folder: F\n    references: [1, 3]\n    cube: {edge: 0.1, base_centre: [0, 0, 0]}\n"
        "    wrong_px: 5\n";
    std::string a = clip, b = clip;
    a.replace(a.find('F'), 1, "a");
    b.replace(b.find('F'), 1, "b");
    suite = parseRealClipSuite("clips:\n  - name: a\n" + a + "  - name: b\n" + b, "suite S");
  }
  RealClipSuiteOptions options() const {
    RealClipSuiteOptions o;
    o.dataRoot = root;
    return o;
  }
};

// A clip whose folder is missing is skipped and named; the found ones keep their files.
TEST(RealClipSuiteBenchmark, AClipWhoseFolderIsMissingIsSkipped) {
  const DataRoot d("RealClipSuiteBenchmarkSkip");
  const RealClipSelection s = selectRealClips(d.suite, d.options());
  ASSERT_EQ(s.found.size(), 1u);
  EXPECT_EQ(s.found[0].clip.name, "a");
  EXPECT_EQ(s.found[0].frames, d.root / "a" / "frames");
  EXPECT_EQ(s.found[0].camera, d.root / "a" / "camera.yml");
  EXPECT_EQ(s.found[0].groundTruth, d.root / "a" / "groundtruth.txt");
  EXPECT_EQ(s.skipped,
            std::vector<std::string>{"b: its folder '" + (d.root / "b").string() + "' is missing"});
  RealClipSuiteOptions only = d.options();
  only.clips = {"a"};
  EXPECT_TRUE(selectRealClips(d.suite, only).skipped.empty());
}

// Bad input is refused before any clip runs, naming what is wrong.
TEST(RealClipSuiteBenchmark, BadInputIsRefusedBeforeAnyClipRuns) {
  const DataRoot d("RealClipSuiteBenchmarkBad");
  const auto refused = [&](const RealClipSuiteOptions& o) {
    return test::errorMessage([&] { selectRealClips(d.suite, o); });
  };
  RealClipSuiteOptions o = d.options();
  o.dataRoot = d.root / "none";
  EXPECT_NE(refused(o).find("data folder '" + (d.root / "none").string() + "' not found"),
            std::string::npos);
  o = d.options();
  o.clips = {"b"};
  std::string m = refused(o);
  EXPECT_NE(
      m.find("none of the suite's clips was found in '" + d.root.string() + "'; b: its folder"),
      std::string::npos)
      << m;
  o.clips = {"c"};
  EXPECT_NE(refused(o).find("--clips: suite S has no clip 'c' (its clips: a, b)"),
            std::string::npos);
  o = d.options();
  fs::rename(d.root / "a" / "camera.yml", d.root / "a" / "cam.yml");
  m = refused(o);
  EXPECT_NE(m.find("clip 'a' (suite S, line 2): its camera '" +
                   (d.root / "a" / "camera.yml").string() + "' is missing"),
            std::string::npos)
      << m;
  std::ofstream(d.root / "a" / "camera.yml") << "image_width: [\n";
  EXPECT_NE(refused(o).find("clip 'a' (suite S, line 2): camera"), std::string::npos);
  fs::rename(d.root / "a" / "cam.yml", d.root / "a" / "camera.yml");
  // A range beyond the folder's frames.
  RealClipSuite longer = d.suite;
  longer.clips[0].lastFrame = 6;
  EXPECT_NE(test::errorMessage([&] {
              selectRealClips(longer, d.options());
            }).find("clip 'a' (suite S, line 2): frame 6 is beyond its 6 frames"),
            std::string::npos);
  // Options.
  o = d.options();
  o.methods = {"reftrack", "surf"};
  EXPECT_NE(test::errorMessage([&] { o.check(); }).find("unknown method 'surf'"),
            std::string::npos);
  o = d.options();
  o.orders = {"sequence", "away:3"};
  EXPECT_NE(test::errorMessage([&] { o.check(); }).find("--order away:3"), std::string::npos);
  o = d.options();
  o.clips = {"a", "a"};
  EXPECT_NE(test::errorMessage([&] { o.check(); }).find("--clips: 'a' given twice"),
            std::string::npos);
  EXPECT_NO_THROW(d.options().check());
}

}  // namespace
}  // namespace reftrack::app
