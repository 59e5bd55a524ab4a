#include "app/simulator/BrickWallScene.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

// A well-mixed 64-bit value of the seed, a salt and two lattice indices (SplitMix64 finaliser).
std::uint64_t hash(std::uint64_t seed, std::uint64_t salt, std::int64_t i, std::int64_t j) {
  std::uint64_t x = seed ^ (salt * 0x9E3779B97F4A7C15ull) ^
                    (static_cast<std::uint64_t>(i) * 0xD1B54A32D192ED03ull) ^
                    (static_cast<std::uint64_t>(j) * 0xAEF17502108EF2D9ull);
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Uniform in [0, 1) from the top 53 bits.
double unit01(std::uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }

// Salts of the noise octaves.
enum Salt : std::uint64_t {
  kUnitSalt = 1,
  kSpeckleFine,
  kSpeckleCoarse,
  kMottle,
  kJointNoise,
  kEdgeNoise,
};

constexpr double kSpeckleFineM = 0.0015, kSpeckleCoarseM = 0.005;  // speckle octaves
constexpr double kMottleM = 0.06;       // the slow shading across a unit (fired bricks vary)
constexpr double kJointNoiseM = 0.003;  // mortar grain
constexpr double kEdgeWaveM = 0.02;     // how fast a unit's edge wanders
constexpr int kMaxChips = 3;            // per unit
// Light reaching the units' sides and the joints' floor, relative to the faces (the light comes
// from the front: the recess is partly shaded).
constexpr float kSideShade = 0.6f, kFloorShade = 0.85f;

}  // namespace

void BrickWallStyle::check() const {
  if (!(unitWidthM > 0.005 && unitWidthM < 5.0))
    throw Error("brick wall style: unitWidthM must be in (0.005, 5)");
  if (!(unitHeightM > 0.005 && unitHeightM < 5.0))
    throw Error("brick wall style: unitHeightM must be in (0.005, 5)");
  if (!(jointM >= 0.0 && jointM < std::min(unitWidthM, unitHeightM)))
    throw Error("brick wall style: jointM must be in [0, the unit's smaller side)");
  for (int c = 0; c < 3; ++c) {
    if (!(unitColour[c] >= 0.0 && unitColour[c] <= 255.0))
      throw Error("brick wall style: unitColour must be within 0..255");
    if (!(jointColour[c] >= 0.0 && jointColour[c] <= 255.0))
      throw Error("brick wall style: jointColour must be within 0..255");
  }
  if (!(unitShadeSpread >= 0.0 && unitShadeSpread <= 1.0))
    throw Error("brick wall style: unitShadeSpread must be in [0, 1]");
  if (!(speckle >= 0.0 && speckle <= 1.0))
    throw Error("brick wall style: speckle must be in [0, 1]");
  if (!(chipsPerUnit >= 0.0 && chipsPerUnit <= kMaxChips))
    throw Error("brick wall style: chipsPerUnit must be in [0, 3]");
  if (!(chipRadius >= 0.0 && chipRadius <= 0.5))
    throw Error("brick wall style: chipRadius must be in [0, 0.5]");
  if (!(chipContrast >= 0.0 && chipContrast < 1.0))
    throw Error("brick wall style: chipContrast must be in [0, 1)");
  if (!(edgeJitterM >= 0.0 && 4.0 * edgeJitterM < std::min(unitWidthM, unitHeightM)))
    throw Error("brick wall style: edgeJitterM must be in [0, a quarter of the unit's side)");
  if (!(jointDepthM >= 0.0 && jointDepthM < 0.1))
    throw Error("brick wall style: jointDepthM must be in [0, 0.1)");
}

BrickWallTexture::BrickWallTexture(std::uint64_t seed, BrickWallStyle style)
    : seed_(hash(seed, 0xB41C4ull, 0, 0)), style_(style) {
  style_.check();
}

double BrickWallTexture::noise(double x, double y, double cellM, std::uint64_t salt) const {
  const double gx = x / cellM, gy = y / cellM;
  const double fx = std::floor(gx), fy = std::floor(gy);
  const auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy);
  double tx = gx - fx, ty = gy - fy;
  tx = tx * tx * (3 - 2 * tx);  // smoothstep: no creases along the lattice
  ty = ty * ty * (3 - 2 * ty);
  const auto v = [&](std::int64_t i, std::int64_t j) {
    return 2.0 * unit01(hash(seed_, salt, i, j)) - 1.0;
  };
  const double top = v(ix, iy) + tx * (v(ix + 1, iy) - v(ix, iy));
  const double bottom = v(ix, iy + 1) + tx * (v(ix + 1, iy + 1) - v(ix, iy + 1));
  return top + ty * (bottom - top);
}

BrickWallTexture::Cell BrickWallTexture::locate(double x, double y) const {
  const BrickWallStyle& s = style_;
  const double pitchX = s.unitWidthM + s.jointM, pitchY = s.unitHeightM + s.jointM;
  const double rowF = std::floor(y / pitchY);
  const auto row = static_cast<std::int64_t>(rowF);
  const bool shifted = s.pattern == BrickWallStyle::Pattern::RunningBond && (row & 1) != 0;
  const double xs = x + (shifted ? 0.5 * pitchX : 0.0);
  const double colF = std::floor(xs / pitchX);
  const auto col = static_cast<std::int64_t>(colF);
  Cell c;
  c.lx = xs - colF * pitchX - 0.5 * s.jointM;  // 0 at the unit's nominal left edge
  c.ly = y - rowF * pitchY - 0.5 * s.jointM;
  const std::uint64_t h = hash(seed_, kUnitSalt, row, col);
  for (std::size_t w = 0; w < c.bits.size(); ++w)
    c.bits[w] = hash(h, kUnitSalt, static_cast<std::int64_t>(w), 0);
  // Each edge set in by its own amount and wandering along its length.
  const double wave = s.edgeJitterM * noise(x, y, kEdgeWaveM, kEdgeNoise);
  const double left = s.edgeJitterM * (1 + c.random(0)) + wave;
  const double right = s.unitWidthM - s.edgeJitterM * (1 + c.random(1)) + wave;
  const double top = s.edgeJitterM * (1 + c.random(2)) + wave;
  const double bottom = s.unitHeightM - s.edgeJitterM * (1 + c.random(3)) + wave;
  c.inUnit = c.lx >= left && c.lx < right && c.ly >= top && c.ly < bottom;
  return c;
}

cv::Vec3f BrickWallTexture::jointColour(double x, double y) const {
  const BrickWallStyle& s = style_;
  const double grain = 1.0 + 0.5 * s.speckle * noise(x, y, kJointNoiseM, kJointNoise);
  return cv::Vec3f(static_cast<float>(s.jointColour[0] * grain),
                   static_cast<float>(s.jointColour[1] * grain),
                   static_cast<float>(s.jointColour[2] * grain));
}

cv::Vec3f BrickWallTexture::unitColour(double x, double y, const Cell& c) const {
  const BrickWallStyle& s = style_;
  // The unit's own shade (Gaussian-ish: the mean of three uniforms) and a slight hue shift.
  const double g = (c.random(4) + c.random(5) + c.random(6) - 1.5) * 2.0;
  double shade = 1.0 + s.unitShadeSpread * g;
  shade *= 1.0 + 0.5 * s.unitShadeSpread * noise(x, y, kMottleM, kMottle);
  shade *= 1.0 + s.speckle * (0.6 * noise(x, y, kSpeckleFineM, kSpeckleFine) +
                              0.4 * noise(x, y, kSpeckleCoarseM, kSpeckleCoarse));
  // Chips and stains: up to kMaxChips round spots per unit, darker or lighter.
  const int chips = static_cast<int>(std::floor(c.random(7) * 2.0 * s.chipsPerUnit + 0.5));
  for (int k = 0; k < std::min(chips, kMaxChips); ++k) {
    const double cx = c.random(10 + 4 * k) * s.unitWidthM;
    const double cy = c.random(11 + 4 * k) * s.unitHeightM;
    const double r =
        s.chipRadius * (0.3 + 0.7 * c.random(12 + 4 * k)) * std::min(s.unitWidthM, s.unitHeightM);
    const double dx = c.lx - cx, dy = c.ly - cy;
    if (dx * dx + dy * dy < r * r)
      shade *= c.random(13 + 4 * k) < 0.6 ? 1.0 - s.chipContrast : 1.0 + s.chipContrast;
  }
  const double hue = 0.06 * (c.random(8) - 0.5);
  return cv::Vec3f(static_cast<float>(s.unitColour[0] * shade * (1 - hue)),
                   static_cast<float>(s.unitColour[1] * shade),
                   static_cast<float>(s.unitColour[2] * shade * (1 + hue)));
}

cv::Vec3f BrickWallTexture::at(double x, double y) const {
  const Cell c = locate(x, y);
  return c.inUnit ? unitColour(x, y, c) : jointColour(x, y);
}

cv::Vec3f BrickWallTexture::seen(double x0, double y0, double x1, double y1) const {
  const Cell face = locate(x0, y0);
  if (face.inUnit) return unitColour(x0, y0, face);
  // Into the joint: the first point along the way (sampled at quarters of the depth) that lies
  // inside a unit is on its side (in shadow); none: the joint's floor (half in shadow).
  for (int k = 1; k <= 4; ++k) {
    const double t = 0.25 * k;
    const double x = x0 + t * (x1 - x0), y = y0 + t * (y1 - y0);
    const Cell side = locate(x, y);
    if (side.inUnit) return unitColour(x, y, side) * kSideShade;
  }
  return jointColour(x1, y1) * kFloorShade;
}

cv::Matx33d planeToImage(const Eigen::Matrix3d& K, const Eigen::Matrix4d& worldToCamera) {
  Eigen::Matrix3d M;
  M.col(0) = worldToCamera.block<3, 1>(0, 0);
  M.col(1) = worldToCamera.block<3, 1>(0, 1);
  M.col(2) = worldToCamera.block<3, 1>(0, 3);
  const Eigen::Matrix3d H = K * M;
  cv::Matx33d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = H(r, c);
  return out;
}

Eigen::Matrix4d wallViewPose(const Eigen::Vector2d& target, double distanceM, double tiltDeg,
                             double azimuthDeg, double rollDeg) {
  if (!(distanceM > 0.0)) throw Error("wall view: the distance must be positive");
  constexpr double kDeg = std::numbers::pi / 180.0;
  const double a = azimuthDeg * kDeg;
  // Camera axes in the world: head-on (looking along +z, x right, y down) tilted about the
  // in-wall axis at the azimuth, then rolled about the optical axis.
  const Eigen::Matrix3d cameraToWorld =
      Eigen::AngleAxisd(tiltDeg * kDeg, Eigen::Vector3d(std::cos(a), std::sin(a), 0.0))
          .toRotationMatrix() *
      Eigen::AngleAxisd(rollDeg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d centre =
      Eigen::Vector3d(target.x(), target.y(), 0.0) - distanceM * cameraToWorld.col(2);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.block<3, 3>(0, 0) = cameraToWorld.transpose();
  T.block<3, 1>(0, 3) = -cameraToWorld.transpose() * centre;
  return T;
}

cv::Mat renderWallView(const BrickWallTexture& wall, const Eigen::Matrix3d& K,
                       const Eigen::Matrix4d& worldToCamera, cv::Size size, int supersample,
                       const Eigen::Vector2d& illuminationGradient, double exposure) {
  if (size.width < 1 || size.height < 1) throw Error("wall view: empty image size");
  if (supersample < 1 || supersample > 16) throw Error("wall view: supersample must be 1..16");
  const cv::Matx33d H = planeToImage(K, worldToCamera);
  if (!(std::abs(cv::determinant(H)) > 0.0))
    throw Error("wall view: the camera sees the wall edge-on");
  const cv::Matx33d inv = H.inv();
  const Eigen::Vector3d centre =
      -worldToCamera.block<3, 3>(0, 0).transpose() * worldToCamera.block<3, 1>(0, 3);
  const double depth = wall.style().jointDepthM;
  cv::Mat out(size, CV_32FC3);
  const double step = 1.0 / supersample, weight = exposure / (supersample * supersample);
  for (int v = 0; v < size.height; ++v) {
    auto* row = out.ptr<cv::Vec3f>(v);
    for (int u = 0; u < size.width; ++u) {
      cv::Vec3d sum(0, 0, 0);
      for (int j = 0; j < supersample; ++j)
        for (int i = 0; i < supersample; ++i) {
          const double px = u - 0.5 + (i + 0.5) * step, py = v - 0.5 + (j + 0.5) * step;
          const double a = inv(0, 0) * px + inv(0, 1) * py + inv(0, 2);
          const double b = inv(1, 0) * px + inv(1, 1) * py + inv(1, 2);
          const double c = inv(2, 0) * px + inv(2, 1) * py + inv(2, 2);
          if (!(c > 0.0)) continue;  // the ray misses the wall (depth 1 / c)
          const double x = a / c, y = b / c;
          const double light =
              std::max(0.2, 1.0 + illuminationGradient.x() * x + illuminationGradient.y() * y);
          // Where the ray would reach the joints' floor (z = depth), along centre -> (x, y, 0).
          const double t = (depth - centre.z()) / (0.0 - centre.z());
          const double x1 = centre.x() + t * (x - centre.x()),
                       y1 = centre.y() + t * (y - centre.y());
          sum += cv::Vec3d(wall.seen(x, y, x1, y1)) * light;
        }
      row[u] = cv::Vec3f(static_cast<float>(sum[0] * weight), static_cast<float>(sum[1] * weight),
                         static_cast<float>(sum[2] * weight));
    }
  }
  return out;
}

}  // namespace reftrack::app
