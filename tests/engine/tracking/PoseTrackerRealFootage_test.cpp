// PoseTracker on real footage: ViSP's hand-held postcard video (../shared/data/planar-videos,
// 161 frames, 640x480, no ground truth, K guessed by ViSP as fx = fy = 840 at the centre).
// The postcard plays the printed marker: its four corners fix the world frame. They are
// hand-clicked once on frame 0, followed through the video by the homography tracker (the scene
// is planar, so a homography maps them exactly) and refined in every frame by cornerSubPix; a
// solvePnP on them gives the "marker" pose of each frame. Two frames with those poses become
// V_A and V_B; the 6-DOF tracker then runs over the whole video, and each of its poses is checked
// against the corners measured in that frame, which the tracker never sees.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <optional>
#include <vector>

#include "TestPaths.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/homography/HomographyTracker.hpp"
#include "engine/reference/ReferencePreparer.hpp"
#include "engine/tracking/PoseTracker.hpp"

namespace reftrack {
namespace {

// Frame-0 corners of the postcard (top-left, top-right, bottom-right, bottom-left as seen),
// clicked by eye on a 40 px grid; cornerSubPix refines them.
const std::array<cv::Point2f, 4> kClickedCorners = {cv::Point2f(64, 115), cv::Point2f(255, 83),
                                                    cv::Point2f(312, 285), cv::Point2f(69, 329)};

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::min<double>(v.size() - 1, p * (v.size() - 1) + 0.5))];
}

struct PostcardFootage {
  std::vector<cv::Mat> frames;
};

std::array<cv::Point2f, 4> refined(const cv::Mat& gray, std::array<cv::Point2f, 4> c) {
  std::vector<cv::Point2f> v(c.begin(), c.end());
  cv::cornerSubPix(gray, v, cv::Size(5, 5), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 40, 0.01));
  std::copy(v.begin(), v.end(), c.begin());
  return c;
}

std::vector<cv::Point3f> rectangle(double width, double height) {
  return {{0, 0, 0},
          {static_cast<float>(width), 0, 0},
          {static_cast<float>(width), static_cast<float>(height), 0},
          {0, static_cast<float>(height), 0}};
}

// solvePnP (IPPE for a plane) of the rectangle; returns the reprojection RMS.
double pnp(const std::vector<cv::Point3f>& object, const std::array<cv::Point2f, 4>& image,
           const cv::Mat& K, cv::Mat& rvec, cv::Mat& tvec) {
  std::vector<cv::Point2f> pts(image.begin(), image.end());
  cv::solvePnP(object, pts, K, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_IPPE);
  std::vector<cv::Point2f> back;
  cv::projectPoints(object, rvec, tvec, K, cv::noArray(), back);
  double sum = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) sum += std::pow(cv::norm(pts[i] - back[i]), 2);
  return std::sqrt(sum / static_cast<double>(pts.size()));
}

// solvePnP's (rvec, tvec) is RigidPose's 6-vector (translation, axis-angle).
RigidPose toPose(const cv::Mat& rvec, const cv::Mat& tvec) {
  Vector6d x;
  x << tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2), rvec.at<double>(0),
      rvec.at<double>(1), rvec.at<double>(2);
  return RigidPose::fromVector6(x);
}

class PoseTrackerRealFootage : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto data = test::sharedDataDir();
    if (!data) return;
    const auto file = *data / "planar-videos" / "video-postcard.mp4";
    cv::VideoCapture video(file.string());
    if (!video.isOpened()) return;
    footage_ = new PostcardFootage;
    for (cv::Mat f; video.read(f);) footage_->frames.push_back(f.clone());
  }
  static void TearDownTestSuite() {
    delete footage_;
    footage_ = nullptr;
  }
  void SetUp() override {
    if (footage_ == nullptr || footage_->frames.empty())
      GTEST_SKIP() << "../shared/data/planar-videos/video-postcard.mp4 not available";
  }
  static PostcardFootage* footage_;
};
PostcardFootage* PoseTrackerRealFootage::footage_ = nullptr;

TEST_F(PoseTrackerRealFootage, PosesAgreeWithThePostcardCornersOnEveryFrame) {
  PostcardFootage& f = *footage_;
  ASSERT_EQ(f.frames.size(), 161u);
  const cv::Size size = f.frames[0].size();
  Eigen::Matrix3d K;
  K << 840, 0, (size.width - 1) * 0.5, 0, 840, (size.height - 1) * 0.5, 0, 0, 1;
  const PinholeCamera camera(K, size);
  cv::Mat Kcv(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Kcv.at<double>(r, c) = K(r, c);

  // 1. The postcard corners in every frame (none where the homography tracker lost the frame):
  // homography from frame 0, refined locally.
  cv::Mat gray0;
  cv::cvtColor(f.frames[0], gray0, cv::COLOR_BGR2GRAY);
  const std::array<cv::Point2f, 4> corners0 = refined(gray0, kClickedCorners);
  HomographyTracker homography(f.frames[0], TrackerParams{});
  std::vector<std::optional<std::array<cv::Point2f, 4>>> corners(f.frames.size());
  for (std::size_t k = 0; k < f.frames.size(); ++k) {
    const HomographyTrackResult h = homography.track(f.frames[k]);
    if (!h.tracked) continue;
    std::vector<cv::Point2f> in(corners0.begin(), corners0.end()), out;
    cv::perspectiveTransform(in, out, cv::Mat(h.H));
    std::array<cv::Point2f, 4> c;
    std::copy(out.begin(), out.end(), c.begin());
    cv::Mat gray;
    cv::cvtColor(f.frames[k], gray, cv::COLOR_BGR2GRAY);
    corners[k] = refined(gray, c);
  }
  const auto followed =
      std::count_if(corners.begin(), corners.end(), [](const auto& c) { return c.has_value(); });
  // Measured: the homography tracker registers every frame of this clip.
  ASSERT_GE(followed, 155) << "the homography tracker lost too many frames of the postcard clip";

  // 2. The postcard's aspect ratio (unknown; the short side is taken as an A6 card's 0.105 m, which
  // only sets the scale) is the one whose rectangle fits the measured corners of a spread of frames
  // best.
  double bestRatio = 1.0, bestRms = 1e9;
  for (double ratio = 0.8; ratio <= 1.8; ratio += 0.005) {
    double rms = 0;
    int n = 0;
    for (std::size_t k = 0; k < corners.size(); k += 20) {
      if (!corners[k]) continue;
      cv::Mat rvec, tvec;
      rms += pnp(rectangle(0.105, 0.105 * ratio), *corners[k], Kcv, rvec, tvec);
      ++n;
    }
    rms /= std::max(n, 1);
    if (rms < bestRms) {
      bestRms = rms;
      bestRatio = ratio;
    }
  }
  const std::vector<cv::Point3f> card = rectangle(0.105, 0.105 * bestRatio);
  RecordProperty("postcard_aspect_ratio", std::to_string(bestRatio));
  RecordProperty("postcard_pnp_rms_px", std::to_string(bestRms));
  // The guessed K and the card's corner rounding limit how well a rectangle fits.
  EXPECT_LT(bestRms, 1.5) << "no rectangle fits the followed postcard corners";

  // 3. References: frame 0 (V_A) and frame 100 (V_B, 3.4 cm away), poses from the postcard.
  const std::size_t a = 0, b = 100;
  ASSERT_TRUE(corners[a] && corners[b]);
  cv::Mat rA, tA, rB, tB;
  pnp(card, *corners[a], Kcv, rA, tA);
  pnp(card, *corners[b], Kcv, rB, tB);
  const RigidPose T_A = toPose(rA, tA), T_B = toPose(rB, tB);
  // Default parameters throughout (measured: a map of 44 points on this low-texture scene).
  const Preparation prep = ReferencePreparer(camera).prepare(
      {f.frames[a], "frame " + std::to_string(a)}, {f.frames[b], "frame " + std::to_string(b)}, T_A,
      T_B, "postcard corners (solvePnP)");
  RecordProperty("reference_matches", std::to_string(prep.map.matches.size()));

  // 4. Track the whole clip; compare each pose with the corners measured in that frame.
  PoseTracker tracker(prep.map, TrackerParams{});
  std::vector<double> errors;
  int tracked = 0;
  for (std::size_t k = 0; k < f.frames.size(); ++k) {
    const PoseTrackingResult r = tracker.process(f.frames[k]);
    if (r.state != TrackingState::Tracking || !r.worldToCamera) continue;
    ++tracked;
    if (!corners[k]) continue;
    double sum = 0;
    for (int i = 0; i < 4; ++i) {
      const cv::Point3f& X = card[static_cast<std::size_t>(i)];
      const Eigen::Vector2d p = camera.project(*r.worldToCamera, Eigen::Vector3d(X.x, X.y, X.z));
      sum += std::hypot(p.x() - (*corners[k])[static_cast<std::size_t>(i)].x,
                        p.y() - (*corners[k])[static_cast<std::size_t>(i)].y);
    }
    errors.push_back(sum / 4.0);
  }
  const double trackedFraction = static_cast<double>(tracked) / f.frames.size();
  RecordProperty("tracked_fraction", std::to_string(trackedFraction));
  RecordProperty("corner_error_median_px", std::to_string(median(errors)));
  RecordProperty("corner_error_p95_px", std::to_string(percentile(errors, 0.95)));
  std::printf(
      "postcard clip: aspect %.3f (PnP RMS %.2f px), %zu reference matches, tracked %d/%zu, "
      "corner error median %.2f px, p95 %.2f px, max %.2f px\n",
      bestRatio, bestRms, prep.map.matches.size(), tracked, f.frames.size(), median(errors),
      percentile(errors, 0.95), percentile(errors, 1.0));
  // Measured: 161 of 161 frames tracked from a map of 44 points; every reported pose agrees
  // with corners the tracker never saw to 0.71 px median, 1.02 px worst. The card corners
  // themselves are only good to ~0.6 px (the rectangle fit's RMS, with a guessed K), so the
  // bounds allow twice that.
  EXPECT_GE(trackedFraction, 0.95);
  EXPECT_LT(median(errors), 1.5);
  EXPECT_LT(percentile(errors, 1.0), 2.5);
}

}  // namespace
}  // namespace reftrack
