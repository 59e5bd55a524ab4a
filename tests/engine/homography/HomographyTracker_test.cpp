#include "engine/homography/HomographyTracker.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/SyntheticImages.hpp"
#include "engine/homography/HomographyDlt.hpp"

using namespace reftrack;

namespace {

TrackerParams homographyParams() {
  TrackerParams p;
  p.mode = TrackingMode::Homography;
  return p;
}

// Reference -> frame k: a slow pan, zoom and in-plane rotation about the image centre.
cv::Matx33d motion(int k, cv::Size size) {
  const double a = 0.004 * k, s = 1.0 + 0.002 * k;
  const double cx = size.width / 2.0, cy = size.height / 2.0;
  const cv::Matx33d C(1, 0, cx, 0, 1, cy, 0, 0, 1);
  const cv::Matx33d M(s * std::cos(a), -s * std::sin(a), 1.5 * k, s * std::sin(a), s * std::cos(a),
                      -0.8 * k, 2e-6 * k, 0, 1);
  return C * M * C.inv();
}

}  // namespace

TEST(HomographyTracker, TracksASyntheticSequenceToSubPixelAccuracy) {
  const cv::Size size(320, 240);
  const cv::Mat world = test::texturedImage(size, 21);
  HomographyTracker tracker(world, homographyParams());
  double worst = 0;
  for (int k = 0; k < 25; ++k) {
    const cv::Matx33d truth = motion(k, size);
    const auto r = tracker.track(test::withNoise(test::warpedBy(world, truth), 2.0, k));
    ASSERT_TRUE(r.tracked) << "frame " << k << ": " << r.failure;
    EXPECT_EQ(r.guided, k > 0);
    EXPECT_GT(r.inlierRatio, 0.5);
    worst = std::max(worst, test::cornerError(r.H, truth, size));
  }
  // Sensor noise SD 2 and 26-44 inliers: the image-corner error (the worst place, extrapolated)
  // measured 0.62 px at most over these 25 frames; the paper's bar is < 1 px.
  EXPECT_LT(worst, 0.8);
}

TEST(HomographyTracker, FlagsALostFrameAndReacquiresUnguided) {
  const cv::Size size(320, 240);
  const cv::Mat world = test::texturedImage(size, 22);
  HomographyTracker tracker(world, homographyParams());
  EXPECT_TRUE(tracker.track(world).tracked);
  const auto lost = tracker.track(test::texturedImage(size, 99));  // an unrelated view
  EXPECT_FALSE(lost.tracked);
  EXPECT_FALSE(lost.failure.empty());
  EXPECT_TRUE(tracker.lost());
  const cv::Matx33d back = motion(10, size);
  const auto again = tracker.track(test::warpedBy(world, back));
  ASSERT_TRUE(again.tracked) << again.failure;
  EXPECT_FALSE(again.guided);
  EXPECT_LT(test::cornerError(again.H, back, size), 0.5);
}

TEST(HomographyTracker, RegistersAThirtyDegreePanGivenTheCamera) {
  // The paper's rotation experiment at its hardest: a 33 degree field of view panned by 30
  // degrees, so the frame shares a ~30 px sliver with the reference; the rest of the frame is
  // unrelated texture. Densely overlapping shapes: the sliver needs distinctive corners, and
  // the corners of sparse flat-filled rectangles all look alike (with the default 128 shapes
  // only 4-5 of 66-102 matches were right).
  const cv::Size size(320, 240);
  const double f = 160.0 / std::tan(16.5 * 3.14159265358979323846 / 180.0);
  Eigen::Matrix3d K;
  K << f, 0, 160, 0, f, 120, 0, 0, 1;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(-30.0 * 3.14159265358979323846 / 180.0, Eigen::Vector3d::UnitY())
          .toRotationMatrix();
  const Eigen::Matrix3d He = K * R * K.inverse();
  cv::Matx33d truth;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) truth(r, c) = He(r, c) / He(2, 2);
  const cv::Mat world = test::texturedImage(size, 24, 800);
  cv::Mat frame = test::texturedImage(size, 97, 800);
  cv::Mat seen;  // where the frame sees the reference
  cv::warpPerspective(cv::Mat(size, CV_8UC1, cv::Scalar(255)), seen, truth, size, cv::INTER_NEAREST,
                      cv::BORDER_CONSTANT, cv::Scalar(0));
  test::warpedBy(world, truth).copyTo(frame, seen);
  frame = test::withNoise(frame, 2.0, 5);

  HomographyTracker tracker(world, homographyParams(), K);
  const auto r = tracker.track(frame);
  ASSERT_TRUE(r.tracked) << r.failure << " matches " << r.matches << " corners " << r.corners;
  EXPECT_FALSE(r.guided);
  EXPECT_GE(r.inliers, 8);
  // Reference points the frame sees land within half a pixel (the annotation target), and no
  // point it does not see is drawn inside it.
  double worst = 0;
  int hiddenDrawn = 0;
  const auto inside = [&](cv::Point2d p) {
    return p.x >= 0 && p.y >= 0 && p.x < size.width && p.y < size.height;
  };
  for (int y = 0; y < size.height; y += 8)
    for (int x = 0; x < size.width; x += 8) {
      const cv::Point2d p(x, y), q = transferPoint(truth, p), drawn = transferPoint(r.H, p);
      if (inside(q))
        worst = std::max(worst, cv::norm(drawn - q));
      else if (inside(drawn) && cv::norm(drawn - q) > 1.0)
        ++hiddenDrawn;
    }
  EXPECT_LT(worst, 0.5);
  EXPECT_EQ(hiddenDrawn, 0);
  // Switched off, the rotation model is not used.
  TrackerParams general = homographyParams();
  general.homography.rotationModel = false;
  EXPECT_FALSE(HomographyTracker(world, general, K).track(frame).rotationModel);
}

TEST(HomographyTracker, StaysRegisteredThroughAPanToThirtyDegreesGivenTheCamera) {
  // A camera turning about its centre by 1 degree per frame, 33 degree field of view, in front
  // of a wide textured plane (reference = its middle): the overlap shrinks to ~9% at 30
  // degrees, where the tracking corners alone no longer hold enough matches.
  const cv::Size size(320, 240);
  const double pi = 3.14159265358979323846;
  const double f = 160.0 / std::tan(16.5 * pi / 180.0);
  Eigen::Matrix3d K;
  K << f, 0, 160, 0, f, 120, 0, 0, 1;
  const cv::Mat wide = test::texturedImage({1600, 480}, 25, 8000);
  const cv::Matx33d fromWide(1, 0, -640, 0, 1, -120, 0, 0, 1);  // wide -> reference pixels
  const auto view = [&](const cv::Matx33d& H, uint64_t seed) {
    cv::Mat out;
    cv::warpPerspective(wide, out, H * fromWide, size, cv::INTER_LINEAR, cv::BORDER_REFLECT);
    return test::withNoise(out, 2.0, seed);
  };
  HomographyTracker tracker(view(cv::Matx33d::eye(), 1), homographyParams(), K);
  double worst = 0;
  for (int deg = 0; deg <= 30; ++deg) {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(deg * pi / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
    const Eigen::Matrix3d He = K * R * K.inverse();
    cv::Matx33d truth;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) truth(r, c) = He(r, c) / He(2, 2);
    const auto r = tracker.track(view(truth, 10 + deg));
    ASSERT_TRUE(r.tracked) << deg << " deg: " << r.failure;
    for (int y = 0; y < size.height; y += 8)
      for (int x = 0; x < size.width; x += 8) {
        const cv::Point2d q = transferPoint(truth, cv::Point2d(x, y));
        if (q.x >= 0 && q.y >= 0 && q.x < size.width && q.y < size.height)
          worst = std::max(worst, cv::norm(transferPoint(r.H, cv::Point2d(x, y)) - q));
      }
  }
  EXPECT_LT(worst, 1.0);
}

TEST(HomographyTracker, KeepsTheGeneralModelOnRealPlanarFootageGivenARoughCamera) {
  // ViSP's hand-held postcard clip: a plane seen by a moving camera, K unknown (fx = fy = 840
  // guessed). The rotation-only model may only stand in where the general fit is thin; here the
  // matches cover the card, so every frame keeps the general homography.
  const auto data = test::sharedDataDir();
  cv::VideoCapture video;
  if (data) video.open((*data / "planar-videos" / "video-postcard.mp4").string());
  if (!video.isOpened())
    GTEST_SKIP() << "../shared/data/planar-videos/video-postcard.mp4 not available";
  std::vector<cv::Mat> frames;
  for (cv::Mat f; video.read(f);) frames.push_back(f.clone());
  ASSERT_EQ(frames.size(), 161u);
  Eigen::Matrix3d K;
  K << 840, 0, 319.5, 0, 840, 239.5, 0, 0, 1;
  HomographyTracker general(frames[0], homographyParams());
  HomographyTracker calibrated(frames[0], homographyParams(), K);
  int tracked = 0, rotation = 0;
  double worst = 0;
  for (const cv::Mat& f : frames) {
    const auto a = general.track(f), b = calibrated.track(f);
    ASSERT_EQ(a.tracked, b.tracked);
    if (!a.tracked) continue;
    ++tracked;
    rotation += b.rotationModel ? 1 : 0;
    worst = std::max(worst, test::cornerError(b.H, a.H, f.size()));
  }
  EXPECT_EQ(tracked, 161);
  EXPECT_EQ(rotation, 0);
  EXPECT_LT(worst, 1e-6);
}

TEST(HomographyTracker, RegistersAFarViewColdThroughTheKeypointLayer) {
  // 45 degrees out of plane, 0.6x, 130 degrees in-plane: square correlation windows cannot match
  // this view; the keypoint homography predicts it and the warped-window correlation refines it.
  const cv::Size size(640, 480);
  const cv::Mat world = test::texturedImage(size, 26);
  const cv::Matx33d truth = test::tiltedView(size, 45.0, 0.6, 130.0);
  cv::Mat frame;
  cv::warpPerspective(world, frame, truth, size, cv::INTER_AREA, cv::BORDER_CONSTANT,
                      cv::Scalar(0));
  frame = test::withNoise(frame, 2.0, 7);
  HomographyTracker tracker(world, homographyParams());
  const auto r = tracker.track(frame);
  ASSERT_TRUE(r.tracked) << r.failure;
  EXPECT_TRUE(r.keypointGuided);
  EXPECT_FALSE(r.guided);
  // Correlation precision at the frame corners (the keypoint homography alone: 1-3 px).
  EXPECT_LT(test::cornerError(r.H, truth, size), 0.5);
  // The next frame is tracked guided by this one.
  const auto next = tracker.track(frame);
  ASSERT_TRUE(next.tracked) << next.failure;
  EXPECT_TRUE(next.guided);
  EXPECT_FALSE(next.keypointGuided);
  // Without the keypoint layer the same view is not registered (or wrongly).
  TrackerParams nccOnly = homographyParams();
  nccOnly.homography.keypoints = KeypointLayer::None;
  const auto old = HomographyTracker(world, nccOnly).track(frame);
  EXPECT_FALSE(old.tracked && test::cornerError(old.H, truth, size) < 1.0);
}

// Every frame of ViSP's hand-held planar clips registered cold (reset before each, frames in a
// shuffled order) gets the same homography as when the clip is tracked in order, to 1 px at the
// frame corners (issue 13's target). The two registrations rest on different matches (corner
// to corner while tracking, warped windows around the keypoint homography when cold); with few
// of them on a small card, their extrapolations to the frame corners differed by up to 16 px
// (measured). Both now end in HomographyRefiner, which aligns the reference warped by H at
// many textured points and re-fits H with Cauchy weights until it stops moving, so the result
// no longer depends on the start (measured: worst 0.37 px on the postcard, 0.02 px on bruegel).
TEST(HomographyTracker, RegistersEveryFrameOfThePlanarClipsColdInShuffledOrder) {
  const auto data = test::sharedDataDir();
  for (const std::string clip : {"video-postcard.mp4", "bruegel.mp4"}) {
    cv::VideoCapture video;
    if (data) video.open((*data / "planar-videos" / clip).string());
    if (!video.isOpened())
      GTEST_SKIP() << "../shared/data/planar-videos/" << clip << " not available";
    std::vector<cv::Mat> frames;
    for (cv::Mat f; video.read(f);) frames.push_back(f.clone());
    ASSERT_GT(frames.size(), 50u);
    HomographyTracker tracker(frames[0], homographyParams());
    std::vector<HomographyTrackResult> inOrder;
    for (const cv::Mat& f : frames) {
      inOrder.push_back(tracker.track(f));
      ASSERT_TRUE(inOrder.back().tracked)
          << clip << " in order, frame " << inOrder.size() - 1 << ": " << inOrder.back().failure;
    }
    std::vector<size_t> order(frames.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    cv::RNG rng(17);
    for (size_t i = order.size() - 1; i > 0; --i)
      std::swap(order[i], order[static_cast<size_t>(rng.uniform(0, static_cast<int>(i) + 1))]);
    std::vector<double> cornerError;
    for (size_t k : order) {
      tracker.reset();
      const auto r = tracker.track(frames[k]);
      ASSERT_TRUE(r.tracked) << clip << " cold, frame " << k << ": " << r.failure;
      EXPECT_FALSE(r.guided);
      EXPECT_TRUE(r.keypointGuided) << clip << " frame " << k;
      cornerError.push_back(test::cornerError(r.H, inOrder[k].H, frames[k].size()));
      // 1 px: the target; the refinement's two results differ by its convergence tolerance
      // (0.01 px per round) plus the few matches that differ near the search boundary.
      EXPECT_LE(cornerError.back(), 1.0) << clip << " frame " << k;
    }
    std::sort(cornerError.begin(), cornerError.end());
    std::printf(
        "%s: %zu frames registered cold; cold vs in order at the frame corners: median "
        "%.2f px, worst %.2f px\n",
        clip.c_str(), frames.size(), cornerError[cornerError.size() / 2], cornerError.back());
  }
}

TEST(HomographyTracker, RejectsBadInput) {
  const cv::Mat world = test::texturedImage({320, 240}, 23);
  HomographyTracker tracker(world, homographyParams());
  // Any frame size is accepted; a black one is lost with the reason.
  const auto black = tracker.track(cv::Mat(100, 100, CV_8UC1, cv::Scalar(0)));
  EXPECT_FALSE(black.tracked);
  EXPECT_NE(black.failure.find("too few corners"), std::string::npos) << black.failure;
  EXPECT_THROW(tracker.track(cv::Mat()), Error);
  EXPECT_THROW(HomographyTracker(cv::Mat(240, 320, CV_8UC1, cv::Scalar(7)), homographyParams()),
               Error);
}

TEST(HomographyTracker, RotationFromHomographyInvertsKRKinv) {
  Eigen::Matrix3d K;
  K << 500, 0, 319.5, 0, 500, 239.5, 0, 0, 1;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1.0, -0.1).normalized()).toRotationMatrix();
  const Eigen::Matrix3d He = 3.7 * K * R * K.inverse();  // any scale
  cv::Matx33d H;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) H(r, c) = He(r, c);
  EXPECT_LT((rotationFromHomography(H, K) - R).norm(), 1e-9);
}

// Oxford affine benchmark (real photographs, exact ground-truth H img1 -> imgN): register
// img2/img3 of the JPEG sequence to img1 with unguided matching. (leuven 1->2 (light) and the
// blur sequences bikes/trees currently fail the 35% inlier test: 20-22% of the reference
// corners become inliers, measured.)
TEST(HomographyTracker, RegistersOxfordPhotometricPairs) {
  const auto data = test::sharedDataDir();
  if (!data) GTEST_SKIP() << "../shared/data not present";
  for (const std::string seq : {"ubc"}) {
    const auto dir = *data / "oxford-photometric" / seq;
    if (!std::filesystem::exists(dir / "img1.png")) GTEST_SKIP() << dir << " missing";
    const cv::Mat ref = cv::imread((dir / "img1.png").string(), cv::IMREAD_GRAYSCALE);
    for (int n : {2, 3}) {
      cv::FileStorage fs((dir / ("H1to" + std::to_string(n) + "p.xml")).string(),
                         cv::FileStorage::READ);
      cv::Mat Hm;
      fs.getFirstTopLevelNode() >> Hm;
      ASSERT_EQ(Hm.rows, 3);
      Hm.convertTo(Hm, CV_64F);
      const cv::Matx33d truth(Hm);
      HomographyTracker tracker(ref, homographyParams());
      const cv::Mat img =
          cv::imread((dir / ("img" + std::to_string(n) + ".png")).string(), cv::IMREAD_GRAYSCALE);
      const auto r = tracker.track(img);
      ASSERT_TRUE(r.tracked) << seq << n << ": " << r.failure;
      const double err = test::cornerError(r.H, truth, ref.size());
      std::printf("oxford %s 1->%d: %d matches, %d inliers, ratio %.2f, corner error %.3f px\n",
                  seq.c_str(), n, r.matches, r.inliers, r.inlierRatio, err);
      // The published H are themselves accurate to ~1 px on these 1000x700 images.
      EXPECT_LT(err, 2.0) << seq << " 1->" << n;
    }
  }
}

TEST(HomographyTracker, ReportsDebugLayersAndStageTimes) {
  const cv::Size size(320, 240);
  const cv::Mat world = test::texturedImage(size, 23);
  HomographyTracker tracker(world, homographyParams());
  const cv::Matx33d truth = motion(3, size);
  const auto r = tracker.track(test::withNoise(test::warpedBy(world, truth), 2.0, 5));
  ASSERT_TRUE(r.tracked) << r.failure;
  EXPECT_EQ(static_cast<int>(r.frameCorners.size()), r.corners);
  EXPECT_EQ(static_cast<int>(r.inlierMatches.size()), r.inliers);
  // Every inlier pair agrees with the true motion within the RANSAC threshold plus the
  // estimation error (1 px at 320x240 + < 0.8 px, as above).
  for (const auto& [ref, cur] : r.inlierMatches) {
    const cv::Point2d q = transferPoint(truth, cv::Point2d(ref.x, ref.y));
    EXPECT_LT(std::hypot(q.x - cur.x, q.y - cur.y), 1.8);
  }
  ASSERT_EQ(r.stageMs.size(), 7u);
  EXPECT_EQ(r.stageMs[0].first, "corners");
  EXPECT_EQ(r.stageMs[3].first, "robust fit");
  EXPECT_EQ(r.stageMs[4].first, "keypoints");  // the cold registration's keypoint layer
  EXPECT_EQ(r.stageMs[5].first, "refine");
  EXPECT_EQ(r.stageMs[6].first, "verify");  // the check of the cold registration
  EXPECT_GT(r.stageMs[6].second, 0.0);
  for (const auto& [name, ms] : r.stageMs) EXPECT_GE(ms, 0.0) << name;
}

// A reference photographed by another camera: frames of other sizes (480x360 and 800x600) seeing
// it scaled, rotated and tilted. Each first frame of a size is registered cold and checked; the
// next frames of that size are tracked from it, all to sub-pixel accuracy at the frame corners.
TEST(HomographyTracker, RegistersFramesOfOtherSizesThanTheReference) {
  const cv::Size refSize(640, 480);
  const cv::Mat world = test::texturedImage(refSize, 27);
  HomographyTracker tracker(world, homographyParams());
  EXPECT_EQ(tracker.referenceSize(), refSize);
  for (const cv::Size size : {cv::Size(480, 360), cv::Size(800, 600)}) {
    const double zoom = size.width / 640.0;
    for (int k = 0; k < 4; ++k) {
      const cv::Matx33d S(zoom, 0, 0, 0, zoom, 0, 0, 0, 1);
      const cv::Matx33d truth = S * test::tiltedView(refSize, 10.0 + 2 * k, 0.9, 15.0 + k);
      const cv::Mat frame = test::withNoise(test::warpedBy(world, truth, size), 2.0, 40 + k);
      const auto r = tracker.track(frame);
      ASSERT_TRUE(r.tracked) << size << " frame " << k << ": " << r.failure;
      EXPECT_EQ(r.guided, k > 0) << size << " frame " << k;
      EXPECT_LT(test::cornerError(r.H, truth, size), 0.5) << size << " frame " << k;
    }
  }
}

// A repeated pattern (bricks in running bond: every brick corner has look-alikes all over) seen
// from 40 degrees, rotated: registered cold to sub-pixel accuracy, and the frame-to-frame
// tracking that follows stays on the right bricks. (The one-to-one keypoint pass is what finds
// the keypoint homography here when the ratio test leaves too few matches.)
TEST(HomographyTracker, RegistersARepeatedBrickPatternFromASteepView) {
  const cv::Size size(640, 480);
  const cv::Mat wall = test::brickWallImage(size, 71);
  HomographyTracker tracker(wall, homographyParams());
  for (int k = 0; k < 3; ++k) {
    const cv::Matx33d truth = test::tiltedView(size, 40.0 + k, 0.8, 25.0 + 2 * k);
    const auto r = tracker.track(test::withNoise(test::warpedBy(wall, truth), 2.0, 50 + k));
    ASSERT_TRUE(r.tracked) << "frame " << k << ": " << r.failure;
    EXPECT_LT(test::cornerError(r.H, truth, size), 1.0) << "frame " << k;
  }
}

// A 3.5x zoom into the reference, rotated by 70 degrees (like the Oxford bark pairs): the scene
// is a textured image four times finer than the reference (which is it downsampled), so the zoomed
// frame shows detail the reference does not, as a real zoom does. Registered on the frame's
// pyramid level 2, where the reference has about its own scale; at full resolution the reference
// windows, sampled 3.5 times finer than its pixels, are blurred copies of the frame's texture
// (measured on the simulated card: 1.2-4.7 px at the frame corners for 3-4x zooms).
TEST(HomographyTracker, RegistersAStrongZoomOnAPyramidLevel) {
  const cv::Size size(640, 480);
  cv::Mat scene(size * 4, CV_8UC1);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      test::texturedImage(size, 100 + 4 * j + i)
          .copyTo(scene(cv::Rect(i * size.width, j * size.height, size.width, size.height)));
  cv::Mat world;
  cv::resize(scene, world, size, 0, 0, cv::INTER_AREA);
  // Reference pixels -> scene pixels: x_scene = 4 x + 1.5 (pixel centres).
  const cv::Matx33d toScene(4, 0, 1.5, 0, 4, 1.5, 0, 0, 1);
  HomographyTracker tracker(world, homographyParams());
  // Measured: 0.72 px at 3.5x, 1.77 px at 4x (without the pyramid levels 5.3 px and lost).
  for (const double zoom : {3.5, 4.0}) {
    const cv::Matx33d truth = test::tiltedView(size, 0.0, zoom, 70.0);
    cv::Mat frame;
    cv::warpPerspective(scene, frame, truth * toScene.inv(), size, cv::INTER_AREA);
    frame = test::withNoise(frame, 2.0, 9);
    tracker.reset();
    const auto r = tracker.track(frame);
    ASSERT_TRUE(r.tracked) << zoom << ": " << r.failure;
    EXPECT_TRUE(r.keypointGuided);
    // At 4x magnification 3 px at the frame corners are 0.75 reference pixels.
    EXPECT_LT(test::cornerError(r.H, truth, size), 3.0) << zoom;
    // Inlier matches come back in full-resolution frame pixels.
    for (const auto& [ref, cur] : r.inlierMatches) {
      const cv::Point2d q = transferPoint(truth, cv::Point2d(ref.x, ref.y));
      EXPECT_LT(std::hypot(q.x - cur.x, q.y - cur.y), 4.0);
    }
  }
}

// A cold registration is reported only once the registration check passes it: with a bound no
// registration can meet under 2 grey levels of noise (the reference warped by H within 0.01 px
// at 320x240 of where the frame shows it, everywhere the frame sees it), the same frame is lost
// and says why.
TEST(HomographyTracker, ReportsNoColdRegistrationTheCheckRefuses) {
  const cv::Size size(640, 480);
  const cv::Mat world = test::texturedImage(size, 29);
  const cv::Matx33d truth = test::tiltedView(size, 30.0, 0.8, 40.0);
  const cv::Mat frame = test::withNoise(test::warpedBy(world, truth), 2.0, 11);
  TrackerParams strict = homographyParams();
  strict.homography.verifyMaxOffsetPx = 0.01;
  const auto refused = HomographyTracker(world, strict).track(frame);
  EXPECT_FALSE(refused.tracked);
  EXPECT_NE(refused.failure.find("refused by the registration check"), std::string::npos)
      << refused.failure;
  strict.homography.verify = false;
  const auto unchecked = HomographyTracker(world, strict).track(frame);
  ASSERT_TRUE(unchecked.tracked) << unchecked.failure;
  EXPECT_EQ(unchecked.stageMs[6].second, 0.0);
  EXPECT_LT(test::cornerError(unchecked.H, truth, size), 0.5);
}

// Photos of an image folder jump from view to view. A frame the tracking around the previous
// frame's homography cannot register is registered cold at once (not only after a coasted
// frame), and a registration carried from the previous frame that moved the view farther than
// 10 px at 320x240 is checked like a cold one; a video's small steps are not checked (the
// verify stage costs nothing there).
TEST(HomographyTracker, RegistersAJumpingPhotoColdAtOnceAndChecksOnlyLargeSteps) {
  const cv::Size size(640, 480);
  const cv::Mat world = test::texturedImage(size, 29);
  HomographyTracker tracker(world, homographyParams());
  const auto frameOf = [&](const cv::Matx33d& truth, int seed) {
    return test::withNoise(test::warpedBy(world, truth), 2.0, seed);
  };
  const cv::Matx33d first = test::tiltedView(size, 10.0, 0.9, 15.0);
  ASSERT_TRUE(tracker.track(frameOf(first, 80)).tracked);
  // A jump: 40 degrees of tilt and 100 degrees of roll from the first view.
  const cv::Matx33d jump = test::tiltedView(size, 45.0, 0.8, 115.0);
  const auto cold = tracker.track(frameOf(jump, 81));
  ASSERT_TRUE(cold.tracked) << cold.failure;
  EXPECT_FALSE(cold.guided);
  EXPECT_LT(test::cornerError(cold.H, jump, size), 1.0);
  EXPECT_GT(cold.stageMs[6].second, 0.0);
  // One pixel on: tracked from the previous frame, not checked.
  const cv::Matx33d step = cv::Matx33d(1, 0, 1, 0, 1, 0, 0, 0, 1) * jump;
  const auto small = tracker.track(frameOf(step, 82));
  ASSERT_TRUE(small.tracked) << small.failure;
  EXPECT_TRUE(small.guided);
  EXPECT_EQ(small.stageMs[6].second, 0.0);
  EXPECT_LT(test::cornerError(small.H, step, size), 1.0);
  // 30 px on (15 px at 320x240): tracked from the previous frame and checked.
  const cv::Matx33d leap = cv::Matx33d(1, 0, 30, 0, 1, 0, 0, 0, 1) * step;
  const auto large = tracker.track(frameOf(leap, 83));
  ASSERT_TRUE(large.tracked) << large.failure;
  EXPECT_TRUE(large.guided);
  EXPECT_GT(large.stageMs[6].second, 0.0);
  EXPECT_LT(test::cornerError(large.H, leap, size), 1.0);
}

// Real photos of buildings and squares (../shared/data/real-photo-pairs, CTU "homogr"), each
// reference's img1 given photos of other scenes (the other pairs' img2, both at half size:
// 300x225 to 856x684): nothing there is the reference, so every registration returned would be
// wrong. The check judges H in its inliers' region only; with chance keypoint matches on
// windows, roofs and sky that region must still be confirmed by correlation, and hold 15% of
// the overlap. Measured: all 14 refused (no homography returned).
TEST(HomographyTracker, RegistersNoPhotoOfAnotherScene) {
  const auto data = test::sharedDataDir();
  if (!data || !std::filesystem::exists(*data / "real-photo-pairs" / "adam" / "img1.png"))
    GTEST_SKIP() << "../shared/data/real-photo-pairs not present";
  const std::vector<std::string> names = {"Boston",      "BruggeSquare", "BruggeTower", "Eiffel",
                                          "ExtremeZoom", "LePoint1",     "adam"};
  const auto half = [&](const std::string& name, const char* image) {
    const cv::Mat full =
        cv::imread((*data / "real-photo-pairs" / name / image).string(), cv::IMREAD_GRAYSCALE);
    cv::Mat small;
    cv::resize(full, small, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
    return small;
  };
  for (size_t i = 0; i < names.size(); ++i) {
    HomographyTracker tracker(half(names[i], "img1.png"), homographyParams());
    for (const size_t other : {(i + 1) % names.size(), (i + 3) % names.size()}) {
      tracker.reset();
      const HomographyTrackResult r = tracker.track(half(names[other], "img2.png"));
      EXPECT_FALSE(r.tracked) << names[i] << " given " << names[other] << ": " << r.check;
      EXPECT_FALSE(r.failure.empty());
    }
  }
}

// A real photo zoomed 6.2x onto a small part of the reference (ExtremeZoom of
// ../shared/data/real-photo-pairs: a town seen from afar, then one street; the part the frame
// shows is 245x162 pixels of the 1519x1006 reference). The reference's 1000 strongest ORB
// keypoints leave ~25 there and no view of them gives a homography (5 inliers): the dense
// reference view, matched to the frame at half its working scale, does. Scored like the pairs
// experiment, the mean deviation from the given homography over the img1 points it maps into
// the frame; the given H comes from ~10 hand-marked points (README of the data), so 5 px is the
// experiment's "within"; measured 1.9 px. Without the dense view: not registered.
TEST(HomographyTracker, RegistersAPhotoZoomedSixTimesOntoAPartOfTheReference) {
  const auto data = test::sharedDataDir();
  const auto dir = data ? *data / "real-photo-pairs" / "ExtremeZoom" : std::filesystem::path();
  if (!data || !std::filesystem::exists(dir / "img1.png"))
    GTEST_SKIP() << "../shared/data/real-photo-pairs not present";
  const cv::Mat reference = cv::imread((dir / "img1.png").string(), cv::IMREAD_GRAYSCALE);
  const cv::Mat frame = cv::imread((dir / "img2.png").string(), cv::IMREAD_GRAYSCALE);
  cv::Matx33d truth;
  std::ifstream in(dir / "H1to2p");
  for (int i = 0; i < 9; ++i) in >> truth.val[i];
  ASSERT_TRUE(in) << "cannot read " << (dir / "H1to2p");
  HomographyTracker tracker(reference, homographyParams());
  const HomographyTrackResult r = tracker.track(frame);
  ASSERT_TRUE(r.tracked) << r.failure;
  EXPECT_TRUE(r.keypointGuided);
  double sum = 0;
  int n = 0;
  for (int y = 0; y < reference.rows; y += 8)
    for (int x = 0; x < reference.cols; x += 8) {
      const cv::Vec3d t = truth * cv::Vec3d(x, y, 1), e = r.H * cv::Vec3d(x, y, 1);
      const cv::Point2d pt(t[0] / t[2], t[1] / t[2]);
      if (pt.x < 0 || pt.y < 0 || pt.x > frame.cols - 1 || pt.y > frame.rows - 1) continue;
      sum += std::hypot(e[0] / e[2] - pt.x, e[1] / e[2] - pt.y);
      ++n;
    }
  ASSERT_GT(n, 100);
  EXPECT_LT(sum / n, 5.0);
}
