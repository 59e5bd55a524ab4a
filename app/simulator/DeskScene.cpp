#include "app/simulator/DeskScene.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <exception>
#include <mutex>
#include <numbers>
#include <opencv2/aruco.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "app/simulator/ProceduralTexture.hpp"
#include "app/simulator/SensorNoise.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

constexpr std::uint64_t kSceneSeed = 20080918;
constexpr double kTileMetres = 0.4;
// Desk and box texels per metre: 0.52 mm texels give >= 2 texels per image pixel down to
// ~0.6 m at 640 px / 60 deg. Walls are seen from >= 1.3 m and get 1.25 mm texels. The marker
// (0.2 m) spans exactly 384 desk texels, 48 per ArUco cell, so its edges fall on texel edges.
constexpr int kDeskTexelsPerTile = 768;
constexpr int kWallTexelsPerTile = 320;
constexpr double kBoxTexelsPerMetre = kDeskTexelsPerTile / kTileMetres;
constexpr double kDeskHalfSide = 1.0, kWallHeight = 1.2;
constexpr double kMarkerSide = 0.2, kQuietZoneCells = 1.5;
constexpr double kPaperGrey = 238.0;

struct Box {
  double x, y, yawDeg, sizeX, sizeY, height;
};
// On the desk around (never between the reference cameras and) the marker.
constexpr std::array<Box, 5> kBoxes = {{{-0.45, 0.25, 25, 0.26, 0.18, 0.12},
                                        {0.45, 0.40, -20, 0.16, 0.16, 0.30},
                                        {0.40, -0.25, 10, 0.22, 0.14, 0.07},
                                        {-0.10, 0.62, -5, 0.36, 0.16, 0.22},
                                        {-0.55, -0.30, 40, 0.12, 0.10, 0.18}}};

// Lambertian brightness of a surface with outward normal n under a light from the front-left.
double shading(const Eigen::Vector3d& n) {
  const Eigen::Vector3d light = Eigen::Vector3d(-0.3, -0.5, 0.8).normalized();
  return 0.55 + 0.45 * std::max(0.0, n.normalized().dot(light));
}

// A textured rectangle: `origin` is the texture's top-left corner, `right` and `down` span it.
render::TexturedMesh quad(const Eigen::Vector3d& origin, const Eigen::Vector3d& right,
                          const Eigen::Vector3d& down, cv::Mat texture) {
  render::TexturedMesh m;
  m.positions = {origin.cast<float>(), (origin + right).cast<float>(),
                 (origin + right + down).cast<float>(), (origin + down).cast<float>()};
  m.uvs = {{0.f, 0.f}, {1.f, 0.f}, {1.f, 1.f}, {0.f, 1.f}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.texture = std::move(texture);
  return m;
}

cv::Mat shaded(const cv::Mat& texture, double brightness) {
  cv::Mat out;
  texture.convertTo(out, CV_8UC3, brightness);
  return out;
}

// The printed marker on its white sheet, pasted into the desk tile `tile` whose top-left corner
// is at world (x0, y0) (texture x = world x, texture down = world -y).
void printMarker(cv::Mat& tile, double x0, double y0, double metresPerTexel,
                 const MarkerSpec& marker) {
  const double quiet = kQuietZoneCells * marker.sideMetres / 8.0;  // 6x6 bits + 2 border cells
  const double h = 0.5 * marker.sideMetres;
  auto texel = [&](double metres) { return metres / metresPerTexel; };
  const double paperX = texel(-h - quiet - x0), paperY = texel(y0 - (h + quiet));
  const double markerX = texel(-h - x0), markerY = texel(y0 - h), side = texel(marker.sideMetres);
  const double sides[] = {paperX, paperY, markerX, markerY, side};
  for (double v : sides)
    if (std::abs(v - std::round(v)) > 1e-6)
      throw Error("desk scene: the marker does not fall on whole desk texels");
  const int sidePx = static_cast<int>(std::lround(side));
  if (sidePx % 8 != 0) throw Error("desk scene: marker texels are not a multiple of 8");
  const int paperSide = static_cast<int>(std::lround(texel(marker.sideMetres + 2 * quiet)));
  tile(cv::Rect(static_cast<int>(std::lround(paperX)), static_cast<int>(std::lround(paperY)),
                paperSide, paperSide))
      .setTo(cv::Scalar::all(kPaperGrey));
  cv::Mat bits, bitsBgr;
  cv::aruco::drawMarker(cv::aruco::getPredefinedDictionary(marker.dictionaryEnum()), marker.id,
                        sidePx, bits, 1);
  // Printed black is not perfectly black, nor the paper perfectly white.
  bits.convertTo(bits, CV_8U, (kPaperGrey - 20.0) / 255.0, 20.0);
  cv::cvtColor(bits, bitsBgr, cv::COLOR_GRAY2BGR);
  bitsBgr.copyTo(tile(cv::Rect(static_cast<int>(std::lround(markerX)),
                               static_cast<int>(std::lround(markerY)), sidePx, sidePx)));
}

// A plane surface split into square tiles, each with its own texture (rasterised from one
// texture field, so the tiles join seamlessly).
void addTiledSurface(std::vector<render::TexturedMesh>& meshes, std::uint64_t seed,
                     const Eigen::Vector3d& origin, const Eigen::Vector3d& rightDir,
                     const Eigen::Vector3d& downDir, double width, double height, int texelsPerTile,
                     const TextureStyle& style, const MarkerSpec* printedMarker = nullptr) {
  const ProceduralTexture field(seed, {width, height}, style);
  const double brightness = shading(downDir.cross(rightDir));
  const int cols = static_cast<int>(std::lround(width / kTileMetres));
  const int rows = static_cast<int>(std::lround(height / kTileMetres));
  std::vector<render::TexturedMesh> tiles(static_cast<std::size_t>(rows * cols));
  // Tiles are independent: rasterised in parallel (scene construction time halves on 2 cores).
  std::exception_ptr failure;  // exceptions must not leave OpenCV's worker threads
  std::mutex failureMutex;
  cv::parallel_for_(cv::Range(0, rows * cols), [&](const cv::Range& range) {
    for (int i = range.start; i < range.end; ++i) {
      try {
        const int r = i / cols, c = i % cols;
        const cv::Rect2d region(c * kTileMetres, r * kTileMetres, kTileMetres, kTileMetres);
        cv::Mat texture = field.rasterize(region, {texelsPerTile, texelsPerTile});
        const Eigen::Vector3d corner = origin + region.x * rightDir + region.y * downDir;
        if (printedMarker) {
          // The desk's texture x runs along world x and its texture down along world -y.
          const double h = 0.5 * printedMarker->sideMetres;
          if (corner.x() < -h && corner.x() + kTileMetres > h && corner.y() > h &&
              corner.y() - kTileMetres < -h)
            printMarker(texture, corner.x(), corner.y(), kTileMetres / texelsPerTile,
                        *printedMarker);
        }
        tiles[static_cast<std::size_t>(i)] = quad(
            corner, kTileMetres * rightDir, kTileMetres * downDir, shaded(texture, brightness));
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failureMutex);
        if (!failure) failure = std::current_exception();
      }
    }
  });
  if (failure) std::rethrow_exception(failure);
  for (render::TexturedMesh& tile : tiles) meshes.push_back(std::move(tile));
}

void addBox(std::vector<render::TexturedMesh>& meshes, std::uint64_t seed, const Box& box) {
  const double yaw = box.yawDeg * std::numbers::pi / 180.0;
  const Eigen::Vector3d ax(std::cos(yaw), std::sin(yaw), 0), ay(-std::sin(yaw), std::cos(yaw), 0);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d base(box.x, box.y, 0);
  const double hx = 0.5 * box.sizeX, hy = 0.5 * box.sizeY;
  TextureStyle style;
  style.base = cv::Scalar(110 + 25 * (seed % 4), 120 + 20 * (seed % 3), 150 - 15 * (seed % 5));
  auto face = [&](const Eigen::Vector3d& origin, const Eigen::Vector3d& right,
                  const Eigen::Vector3d& down, std::uint64_t faceSeed) {
    const double w = right.norm(), h = down.norm();
    const ProceduralTexture field(faceSeed, {w, h}, style);
    const cv::Size texels(static_cast<int>(std::lround(w * kBoxTexelsPerMetre)),
                          static_cast<int>(std::lround(h * kBoxTexelsPerMetre)));
    const cv::Mat texture = field.rasterize({0, 0, w, h}, texels);
    meshes.push_back(quad(origin, right, down, shaded(texture, shading(down.cross(right)))));
  };
  const Eigen::Vector3d top = base + box.height * up;
  // Top face, read with the box's +y away from the viewer; then the four sides seen from outside.
  face(top - hx * ax + hy * ay, 2 * hx * ax, -2 * hy * ay, mixSeed(seed, 0));
  const Eigen::Vector3d drop = -box.height * up;
  face(top - hx * ax - hy * ay, 2 * hx * ax, drop, mixSeed(seed, 1));   // front (-y)
  face(top + hx * ax - hy * ay, 2 * hy * ay, drop, mixSeed(seed, 2));   // right (+x)
  face(top + hx * ax + hy * ay, -2 * hx * ax, drop, mixSeed(seed, 3));  // back (+y)
  face(top - hx * ax + hy * ay, -2 * hy * ay, drop, mixSeed(seed, 4));  // left (-x)
}

}  // namespace

DeskScene buildDeskScene() {
  DeskScene scene;
  scene.marker.dictionary = "DICT_6X6_250";
  scene.marker.id = 23;
  scene.marker.sideMetres = kMarkerSide;
  scene.marker.check();
  scene.contentCentre = Eigen::Vector3d(0.0, 0.2, 0.06);
  scene.referenceEyeA = Eigen::Vector3d(-0.125, -0.52, 0.74);
  scene.referenceEyeB = scene.referenceEyeA + Eigen::Vector3d(0.25, 0.0, 0.0);

  // Boxes first: drawn before the desk and walls they hide, their depth lets the rasteriser skip
  // the hidden fragments.
  for (std::size_t i = 0; i < kBoxes.size(); ++i)
    addBox(scene.meshes, mixSeed(kSceneSeed, 100 + i), kBoxes[i]);
  const double d = kDeskHalfSide;
  const Eigen::Vector3d ex = Eigen::Vector3d::UnitX(), ey = Eigen::Vector3d::UnitY(),
                        ez = Eigen::Vector3d::UnitZ();
  TextureStyle desk;
  desk.base = cv::Scalar(120, 150, 175);  // light wood-ish
  addTiledSurface(scene.meshes, mixSeed(kSceneSeed, 1), {-d, d, 0}, ex, -ey, 2 * d, 2 * d,
                  kDeskTexelsPerTile, desk, &scene.marker);
  TextureStyle wall;
  wall.base = cv::Scalar(170, 165, 160);
  wall.shapesPerSquareMetre = 250.0;  // seen from further: fewer, larger shapes
  wall.minShapeMetres = 0.015;
  wall.maxShapeMetres = 0.35;
  wall.strokesPerSquareMetre = 60.0;
  addTiledSurface(scene.meshes, mixSeed(kSceneSeed, 2), {-d, d, kWallHeight}, ex, -ez, 2 * d,
                  kWallHeight, kWallTexelsPerTile, wall);  // back
  addTiledSurface(scene.meshes, mixSeed(kSceneSeed, 3), {-d, -d, kWallHeight}, ey, -ez, 2 * d,
                  kWallHeight, kWallTexelsPerTile, wall);  // left
  addTiledSurface(scene.meshes, mixSeed(kSceneSeed, 4), {d, d, kWallHeight}, -ey, -ez, 2 * d,
                  kWallHeight, kWallTexelsPerTile, wall);  // right
  return scene;
}

}  // namespace reftrack::app
