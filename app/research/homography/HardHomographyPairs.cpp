#include "app/research/homography/HardHomographyPairs.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/research/homography/SyntheticViews.hpp"
#include "app/simulator/BrickWallScene.hpp"
#include "app/simulator/PhotometricEffects.hpp"
#include "app/simulator/SensorNoise.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/PinholeCamera.hpp"

namespace reftrack::app {

namespace {

// One synthesised frame: its geometry and its photometric change.
struct ViewSpec {
  double tiltDeg, azimuthDeg, scale, rollDeg;
  double gain, offset;
  double gradientX, gradientY;  // relative brightness change, centre to the farthest corner
};

// graf: the camera swings sideways about the wall (tilt about the vertical axis), a little
// rolled, under changing light.
constexpr ViewSpec kGrafViews[] = {
    {20, 90, 1.0, 2, 1.05, 4, 0.10, 0.05},   {30, 90, 0.97, -3, 0.92, -6, -0.12, 0.04},
    {40, 90, 0.95, 4, 1.10, 2, 0.08, -0.10}, {50, 90, 0.93, -2, 0.88, 8, -0.15, -0.05},
    {60, 90, 0.9, 3, 1.00, -4, 0.12, 0.10},
};
// boat and bark: zoom with in-plane rotation (boat to ~2.9x, bark to 4x, as Oxford's).
constexpr ViewSpec kBoatViews[] = {
    {0, 0, 1.3, 10, 1.04, 3, 0.08, 0.02},  {0, 0, 1.7, 25, 0.94, -4, -0.1, 0.06},
    {0, 0, 2.1, 40, 1.08, 5, 0.05, -0.12}, {0, 0, 2.5, 55, 0.90, -2, -0.08, -0.08},
    {0, 0, 2.9, 70, 1.02, 6, 0.12, 0.06},
};
constexpr ViewSpec kBarkViews[] = {
    {0, 0, 1.4, 15, 0.95, 5, 0.06, 0.08},  {0, 0, 1.9, 35, 1.06, -3, -0.1, -0.04},
    {0, 0, 2.5, 55, 0.92, 4, 0.12, -0.06}, {0, 0, 3.1, 80, 1.08, -5, -0.06, 0.1},
    {0, 0, 4.0, 100, 0.97, 2, 0.08, -0.1},
};
// The simulated walls: viewpoints of the brick wall, zoom (+ slight tilt) of the tiles.
constexpr ViewSpec kWallViews[] = {
    {20, 90, 1.0, 1, 1.04, 0, 0, 0},  {30, 90, 0.97, -2, 0.93, 0, 0, 0},
    {40, 90, 0.95, 2, 1.08, 0, 0, 0}, {50, 90, 0.93, -1, 0.90, 0, 0, 0},
    {60, 90, 0.9, 2, 1.00, 0, 0, 0},
};
constexpr ViewSpec kTileViews[] = {
    {20, 30, 1.2, 10, 1.05, 0, 0, 0},  {30, 120, 1.5, 40, 0.92, 0, 0, 0},
    {40, 200, 1.0, 90, 1.08, 0, 0, 0}, {25, 300, 2.0, 150, 0.95, 0, 0, 0},
    {15, 60, 2.5, 250, 1.02, 0, 0, 0},
};

const char* kindOf(const ViewSpec& v) {
  return v.tiltDeg >= 20 && v.scale < 1.2 ? "viewpoint" : "zoom-rotation";
}

std::string labelOf(const ViewSpec& v) {
  char label[96];
  std::snprintf(label, sizeof label, "tilt %.0f az %.0f scale %.1f roll %.0f", v.tiltDeg,
                v.azimuthDeg, v.scale, v.rollDeg);
  return label;
}

// What a camera adds to an ideal CV_32FC3 view before it is stored: defocus (a disc of
// `defocusPx`), vignetting (20% at the corners), sensor noise and JPEG compression at
// `jpegQuality`; returned grey, as the experiment registers it.
cv::Mat photographed(const cv::Mat& ideal, double defocusPx, int jpegQuality, double noiseSigma,
                     std::uint64_t seed) {
  cv::Mat lit = defocus(ideal, defocusPx);
  std::vector<cv::Mat> gain(3, vignettingGain(lit.size(), 0.2));
  cv::Mat gain3;
  cv::merge(gain, gain3);
  lit = lit.mul(gain3);
  const cv::Mat noisy = addSensorNoise(lit, seed, noiseSigma);
  std::vector<uchar> jpeg;
  cv::imencode(".jpg", noisy, jpeg, {cv::IMWRITE_JPEG_QUALITY, jpegQuality});
  return cv::imdecode(jpeg, cv::IMREAD_GRAYSCALE);
}

// Defocus of frame i (pixels): every frame focused a little differently from the reference.
double frameDefocusPx(int i) { return 0.5 + 0.15 * (i % 4); }
constexpr double kReferenceDefocusPx = 0.5;
constexpr int kFrameJpegQuality = 80, kReferenceJpegQuality = 90;

// Views of img1 of `folder` cut to `size` (centred), or nothing when it is missing.
void imageSet(std::vector<HomographyPair>& out, const std::string& name,
              const std::filesystem::path& image, cv::Size size, const ViewSpec* views, int count,
              double noiseSigma, std::uint64_t seed) {
  if (!std::filesystem::exists(image)) return;
  const cv::Mat full = cv::imread(image.string(), cv::IMREAD_GRAYSCALE);
  if (full.empty()) throw Error("hard pairs: cannot read " + image.string());
  if (full.cols < size.width || full.rows < size.height)
    throw Error("hard pairs: " + image.string() + " is smaller than the set's size");
  const cv::Rect cut((full.cols - size.width) / 2, (full.rows - size.height) / 2, size.width,
                     size.height);
  const cv::Mat reference = full(cut).clone();
  for (int i = 0; i < count; ++i) {
    const ViewSpec& v = views[i];
    const cv::Matx33d H =
        syntheticViewHomography(size, v.tiltDeg, v.azimuthDeg, v.scale, v.rollDeg);
    const cv::Mat view = synthesiseView(reference, H, 0.0, 0, size, cv::BORDER_REFLECT_101);
    const cv::Mat lit = relight(view, v.gain, v.offset, {v.gradientX, v.gradientY});
    cv::Mat bgr;
    cv::cvtColor(lit, bgr, cv::COLOR_GRAY2BGR);
    bgr.convertTo(bgr, CV_32FC3);
    const cv::Mat frame = photographed(bgr, frameDefocusPx(i), kFrameJpegQuality, noiseSigma,
                                       mixSeed(seed, static_cast<std::uint64_t>(i)));
    out.push_back({name, kindOf(v), labelOf(v), reference, frame, H});
  }
}

// Views of a simulated wall: the reference head-on from camera `refCamera`, frames from
// `frameCamera` looking at points near the reference's centre, scale = frame pixels per
// reference pixel there.
void wallSet(std::vector<HomographyPair>& out, const std::string& name,
             const BrickWallTexture& wall, const PinholeCamera& refCamera, double refDistanceM,
             const PinholeCamera& frameCamera, const ViewSpec* views, int count, double noiseSigma,
             std::uint64_t seed, int supersample) {
  const Eigen::Vector2d gradient(0.04, -0.03);  // the wall's light (per metre)
  const Eigen::Matrix4d refPose = wallViewPose({0, 0}, refDistanceM, 0, 0, 0);
  const cv::Matx33d refPlane = planeToImage(refCamera.K(), refPose);
  const cv::Mat reference = photographed(
      renderWallView(wall, refCamera.K(), refPose, refCamera.imageSize(), supersample, gradient),
      kReferenceDefocusPx, kReferenceJpegQuality, noiseSigma, mixSeed(seed, 100));
  const double fRatio = frameCamera.K()(0, 0) / refCamera.K()(0, 0);
  for (int i = 0; i < count; ++i) {
    const ViewSpec& v = views[i];
    const Eigen::Vector2d target(0.04 * (i % 3 - 1), 0.03 * ((i + 1) % 3 - 1));
    const Eigen::Matrix4d pose =
        wallViewPose(target, refDistanceM * fRatio / v.scale, v.tiltDeg, v.azimuthDeg, v.rollDeg);
    cv::Matx33d truth = planeToImage(frameCamera.K(), pose) * refPlane.inv();
    truth *= 1.0 / truth(2, 2);
    const cv::Mat frame =
        photographed(renderWallView(wall, frameCamera.K(), pose, frameCamera.imageSize(),
                                    supersample, gradient, v.gain),
                     frameDefocusPx(i), kFrameJpegQuality, noiseSigma,
                     mixSeed(seed, static_cast<std::uint64_t>(i)));
    out.push_back({name, kindOf(v), labelOf(v), reference, frame, truth});
  }
}

}  // namespace

const std::vector<std::string>& hardPairSetNames() {
  static const std::vector<std::string> names = {"graf-sim", "wall-sim", "boat-sim", "bark-sim",
                                                 "tiles-sim"};
  return names;
}

std::vector<HomographyPair> buildHardHomographyPairs(const std::filesystem::path& dataDir,
                                                     double noiseSigma, std::uint64_t seed,
                                                     int wallSupersample) {
  std::vector<HomographyPair> out;
  imageSet(out, "graf-sim", dataDir / "ubc" / "img1.png", {800, 640}, kGrafViews, 5, noiseSigma,
           mixSeed(seed, 1));
  {
    // Bricks of 215 x 65 mm; the reference (55 degree view) sees 3 m of the wall, the frames
    // come from a narrower camera of another size.
    const BrickWallTexture bricks(mixSeed(seed, 2));
    wallSet(out, "wall-sim", bricks, PinholeCamera::fromFieldOfView({1000, 700}, 55.0),
            1.5 / std::tan(27.5 * std::numbers::pi / 180.0),
            PinholeCamera::fromFieldOfView({880, 680}, 50.0), kWallViews, 5, noiseSigma,
            mixSeed(seed, 3), wallSupersample);
  }
  imageSet(out, "boat-sim", dataDir / "bikes" / "img1.png", {850, 680}, kBoatViews, 5, noiseSigma,
           mixSeed(seed, 4));
  imageSet(out, "bark-sim", dataDir / "trees" / "img1.png", {765, 512}, kBarkViews, 5, noiseSigma,
           mixSeed(seed, 5));
  {
    // Square tiles of 100 mm with 4 mm joints; the reference sees 1.25 m of them.
    BrickWallStyle tiles;
    tiles.pattern = BrickWallStyle::Pattern::Tiles;
    tiles.unitWidthM = tiles.unitHeightM = 0.1;
    tiles.jointM = 0.004;
    tiles.unitColour = cv::Scalar(150, 175, 195);
    tiles.jointColour = cv::Scalar(90, 95, 100);
    tiles.unitShadeSpread = 0.08;
    tiles.edgeJitterM = 0.0005;
    tiles.jointDepthM = 0.002;
    tiles.chipsPerUnit = 0.3;
    tiles.chipRadius = 0.1;
    tiles.chipContrast = 0.15;
    const BrickWallTexture wall(mixSeed(seed, 6), tiles);
    wallSet(out, "tiles-sim", wall, PinholeCamera::fromFieldOfView({800, 600}, 55.0),
            0.625 / std::tan(27.5 * std::numbers::pi / 180.0),
            PinholeCamera::fromFieldOfView({640, 480}, 60.0), kTileViews, 5, noiseSigma,
            mixSeed(seed, 7), wallSupersample);
  }
  return out;
}

void saveHomographyPairs(const std::vector<HomographyPair>& pairs,
                         const std::filesystem::path& dir) {
  std::string sequence;
  int k = 1;
  for (const HomographyPair& p : pairs) {
    const std::filesystem::path folder = dir / p.sequence;
    if (p.sequence != sequence) {
      sequence = p.sequence;
      k = 1;
      std::filesystem::create_directories(folder);
      if (!cv::imwrite((folder / "img1.png").string(), p.reference))
        throw Error("cannot write " + (folder / "img1.png").string());
    }
    if (++k > 6) throw Error("save pairs: more than 5 frames in set " + p.sequence);
    const std::string n = std::to_string(k);
    if (!cv::imwrite((folder / ("img" + n + ".png")).string(), p.frame))
      throw Error("cannot write " + (folder / ("img" + n + ".png")).string());
    cv::FileStorage fs((folder / ("H1to" + n + "p.xml")).string(), cv::FileStorage::WRITE);
    fs << "H1to" + n + "p" << cv::Mat(p.truth);
  }
}

}  // namespace reftrack::app
