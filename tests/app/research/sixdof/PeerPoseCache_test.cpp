#include "app/research/sixdof/PeerPoseCache.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"

namespace reftrack::app {
namespace {

namespace fs = std::filesystem;

// An image folder of six small noise frames (000000.png ..), and the inputs of a SIFT peer over
// frames 1..4 with references 1 and 3.
struct CacheFixture {
  fs::path dir, frames, cacheDir;
  PeerPoseInputs inputs;
  explicit CacheFixture(const std::string& name) {
    dir = test::freshTempDir(name);
    frames = dir / "frames";
    cacheDir = dir / "cache";
    fs::create_directories(frames);
    cv::RNG rng(5);
    for (int k = 0; k < 6; ++k) {
      cv::Mat image(24, 32, CV_8UC3);
      rng.fill(image, cv::RNG::UNIFORM, 0, 255);
      cv::imwrite((frames / ("00000" + std::to_string(k) + ".png")).string(), image);
    }
    inputs.detector = "sift";
    inputs.frameFiles = frameFilesOf(frames.string(), 1, 4);
    inputs.references = {1, 3};
    inputs.referencePoses = {pose(0.1), pose(0.2)};
    Eigen::Matrix3d K;
    K << 30, 0, 15.5, 0, 30, 11.5, 0, 0, 1;
    inputs.camera = PinholeCamera(K, cv::Size(32, 24), {-0.1, 0.01, 0, 0, 0});
  }
  // A pose whose numbers have no short decimal form.
  static RigidPose pose(double a) {
    return RigidPose(rotationFromAxisAngle(Eigen::Vector3d(a, std::sqrt(2.0) * a, -a / 3.0)),
                     Eigen::Vector3d(std::sqrt(a), -a / 7.0, 1.0 / 3.0));
  }
};

// What a peer gave the four frames: poses, one frame without (its reason), CPU times.
PeerPoses somePoses() {
  PeerPoses p;
  p.method = "SIFT+PnP";
  p.modelPoints = 77;
  p.poses = {CacheFixture::pose(0.11), std::nullopt, CacheFixture::pose(0.37),
             CacheFixture::pose(1.0 / 3.0)};
  p.reasons = {"", "too few 2D-3D matches", "", ""};
  p.cpuMs = {101.123456789, 99.5, 1.0 / 7.0, 120.0};
  return p;
}

void expectIdentical(const PeerPoses& a, const PeerPoses& b) {
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.modelPoints, b.modelPoints);
  EXPECT_EQ(a.modelError, b.modelError);
  EXPECT_EQ(a.reasons, b.reasons);
  EXPECT_EQ(a.cpuMs, b.cpuMs);  // bit for bit
  ASSERT_EQ(a.poses.size(), b.poses.size());
  for (std::size_t k = 0; k < a.poses.size(); ++k) {
    ASSERT_EQ(a.poses[k].has_value(), b.poses[k].has_value()) << k;
    if (!a.poses[k]) continue;
    EXPECT_TRUE(a.poses[k]->rotation() == b.poses[k]->rotation()) << k;  // bit for bit
    EXPECT_TRUE(a.poses[k]->translation() == b.poses[k]->translation()) << k;
  }
}

// Stored once, the poses come back bit for bit without computing; any input that changes them
// (a frame file touched, a reference's pose, the camera, the peer's settings, the detector) is
// computed again.
TEST(PeerPoseCache, ReturnsIdenticalPosesAndIsInvalidatedWhenAnInputChanges) {
  CacheFixture f("PeerPoseCache");
  const PeerPoseCache cache(f.cacheDir);
  int computed = 0;
  const auto compute = [&] {
    ++computed;
    return somePoses();
  };
  bool fromCache = true;
  std::string why;
  expectIdentical(cache.getOrCompute(f.inputs, compute, fromCache, why), somePoses());
  EXPECT_FALSE(fromCache);
  EXPECT_EQ(computed, 1);
  EXPECT_NE(why.find("none cached; computed and stored in"), std::string::npos) << why;
  expectIdentical(cache.getOrCompute(f.inputs, compute, fromCache, why), somePoses());
  EXPECT_TRUE(fromCache);
  EXPECT_EQ(computed, 1);
  EXPECT_NE(why.find("cached in '" + f.cacheDir.string()), std::string::npos) << why;

  const auto changed = [&](const PeerPoseInputs& inputs) {
    const int before = computed;
    cache.getOrCompute(inputs, compute, fromCache, why);
    return computed == before + 1 && !fromCache;
  };
  const fs::path frame = f.frames / "000002.png";
  fs::last_write_time(frame, fs::last_write_time(frame) + std::chrono::seconds(5));
  EXPECT_TRUE(changed(f.inputs));  // the same file list, one file's time changed
  EXPECT_FALSE(changed(f.inputs));
  PeerPoseInputs other = f.inputs;
  Eigen::Matrix3d R = other.referencePoses[1].rotation();
  R(0, 0) = std::nextafter(R(0, 0), 2.0);
  other.referencePoses[1] = RigidPose(R, other.referencePoses[1].translation());
  EXPECT_TRUE(changed(other));
  other = f.inputs;
  other.references = {1, 4};
  EXPECT_TRUE(changed(other));
  other = f.inputs;
  other.camera = PinholeCamera(f.inputs.camera.K(), cv::Size(32, 24), {-0.1, 0.02, 0, 0, 0});
  EXPECT_TRUE(changed(other));
  other = f.inputs;
  other.params.ratioTest = 0.75f;
  EXPECT_TRUE(changed(other));
  other = f.inputs;
  other.frameFiles = frameFilesOf(f.frames.string(), 1, 3);  // one frame fewer
  EXPECT_TRUE(changed(other));
  other = f.inputs;
  other.detector = "orb";
  EXPECT_TRUE(changed(other));
  EXPECT_NE(cache.fileFor("orb", peerPoseCacheKey(other)),
            cache.fileFor("sift", peerPoseCacheKey(other)));
  // The key names the files, not their folder: the same files elsewhere share it.
  const fs::path copy = f.dir / "copy";
  fs::copy(f.frames, copy);
  for (const fs::path& file : f.inputs.frameFiles)
    fs::last_write_time(copy / file.filename(), fs::last_write_time(file));
  other = f.inputs;
  other.frameFiles = frameFilesOf(copy.string(), 1, 4);
  EXPECT_EQ(peerPoseCacheKey(other), peerPoseCacheKey(f.inputs));
}

// A damaged or foreign file under the key's name is not trusted: computed again and rewritten.
TEST(PeerPoseCache, ADamagedFileIsComputedAgain) {
  CacheFixture f("PeerPoseCacheDamaged");
  const PeerPoseCache cache(f.cacheDir);
  const std::string key = peerPoseCacheKey(f.inputs);
  cache.store("sift", key, somePoses());
  const fs::path file = cache.fileFor("sift", key);
  std::string text = test::readTextFile(file);
  text.replace(text.rfind("end"), 3, "");  // cut short
  std::ofstream(file) << text;
  std::string why;
  EXPECT_FALSE(cache.load("sift", key, why));
  EXPECT_NE(why.find("is unreadable (no end line)"), std::string::npos) << why;
  EXPECT_FALSE(cache.load("sift", key + "frame x 1 1\n", why));
  EXPECT_NE(why.find("none cached"), std::string::npos) << why;  // another file name
  std::ofstream(cache.fileFor("sift", key)) << "something else\n";
  EXPECT_FALSE(cache.load("sift", key, why));
  EXPECT_NE(why.find("not a peer-pose file"), std::string::npos) << why;
  bool fromCache = true;
  int computed = 0;
  cache.getOrCompute(
      f.inputs,
      [&] {
        ++computed;
        return somePoses();
      },
      fromCache, why);
  EXPECT_EQ(computed, 1);
  std::optional<PeerPoses> back = cache.load("sift", key, why);
  ASSERT_TRUE(back) << why;
  expectIdentical(*back, somePoses());
}

TEST(PeerPoseCache, FrameFilesOfARangeOrAVideo) {
  CacheFixture f("PeerPoseCacheFiles");
  const std::vector<fs::path> files = frameFilesOf(f.frames.string(), 2, 3);
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0].filename(), "000002.png");
  EXPECT_EQ(files[2].filename(), "000004.png");
  EXPECT_EQ(frameFilesOf(f.frames.string(), 4, 0).size(), 2u);  // to the end
  EXPECT_NE(test::errorMessage([&] {
              frameFilesOf(f.frames.string(), 4, 3);
            }).find("holds 6 images: frames 4 .. 6 are not all there"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] {
              frameFilesOf("tum:" + f.dir.string(), 0, 0);
            }).find("takes an image folder or a video"),
            std::string::npos);
  std::ofstream(f.dir / "clip.mp4") << "not really a video";
  EXPECT_EQ(frameFilesOf((f.dir / "clip.mp4").string(), 5, 10),
            std::vector<fs::path>{f.dir / "clip.mp4"});
}

}  // namespace
}  // namespace reftrack::app
