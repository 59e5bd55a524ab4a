#include "app/simulator/ProceduralTexture.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "app/simulator/SensorNoise.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

constexpr double kPi = std::numbers::pi;
// Value-noise octaves: cell size (m) and amplitude (grey levels, before interpolation). The
// coarse ones shade the background; the fine ones overlay everything, shapes included, so flat
// areas keep some texture as real surfaces do. Cells are whole multiples of the noise grid.
constexpr std::array<std::pair<double, double>, 2> kCoarseOctaves = {{{0.3, 30.0}, {0.1, 18.0}}};
constexpr std::array<std::pair<double, double>, 3> kFineOctaves = {
    {{0.03, 14.0}, {0.01, 11.0}, {0.004, 9.0}}};
// Octaves are summed once per surface on this grid (cubic upsampling of each octave's random
// values) and sampled bilinearly per tile: per-texel cubic warps of every octave were ~30x slower.
constexpr double kNoiseGridMetres = 0.002;
// Texels drawn beyond each side of a raster and cropped: OpenCV's anti-aliased edges differ
// where they are clipped by the image border, which would leave seams between tiles.
constexpr int kMarginTexels = 4;
constexpr int kShift = 4;  // sub-pixel bits of the OpenCV drawing calls

cv::Rect2d boundsOf(const std::vector<cv::Point2d>& pts) {
  double x0 = pts[0].x, x1 = pts[0].x, y0 = pts[0].y, y1 = pts[0].y;
  for (const auto& p : pts) {
    x0 = std::min(x0, p.x);
    x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y);
    y1 = std::max(y1, p.y);
  }
  return {x0, y0, x1 - x0, y1 - y0};
}

}  // namespace

void TextureStyle::check() const {
  for (int c = 0; c < 3; ++c)
    if (!(base[c] >= 0.0 && base[c] <= 255.0))
      throw Error("texture style base colour must be within 0..255");
  if (!(shapesPerSquareMetre >= 0.0 && shapesPerSquareMetre < 1e5))
    throw Error("texture style shapesPerSquareMetre must be in [0, 1e5)");
  if (!(minShapeMetres > 0.0 && maxShapeMetres >= minShapeMetres && maxShapeMetres < 10.0))
    throw Error("texture style minShapeMetres/maxShapeMetres must satisfy 0 < min <= max < 10");
  if (!(strokesPerSquareMetre >= 0.0 && strokesPerSquareMetre < 1e5))
    throw Error("texture style strokesPerSquareMetre must be in [0, 1e5)");
  if (!(noiseAmplitude >= 0.0 && noiseAmplitude <= 10.0))
    throw Error("texture style noiseAmplitude must be in [0, 10]");
}

ProceduralTexture::ProceduralTexture(std::uint64_t seed, cv::Size2d surfaceMetres,
                                     TextureStyle style)
    : size_(surfaceMetres), style_(style) {
  style_.check();
  if (!(size_.width > 0.0 && size_.height > 0.0 && size_.width < 100.0 && size_.height < 100.0))
    throw Error("procedural texture surface must be between 0 and 100 m on each side");
  cv::RNG rng(mixSeed(seed, 0x746578747572ull));

  const cv::Size gridSize(static_cast<int>(std::ceil(size_.width / kNoiseGridMetres)) + 1,
                          static_cast<int>(std::ceil(size_.height / kNoiseGridMetres)) + 1);
  auto sumOctaves = [&](const auto& octaves) {
    cv::Mat field(gridSize, CV_32FC3, cv::Scalar::all(0));
    for (const auto& [cell, amplitude] : octaves) {
      const int factor = static_cast<int>(std::lround(cell / kNoiseGridMetres));
      cv::Mat values((gridSize.height + factor - 1) / factor + 3,
                     (gridSize.width + factor - 1) / factor + 3, CV_32FC3);
      const double a = amplitude * style_.noiseAmplitude;
      for (int r = 0; r < values.rows; ++r)
        for (int c = 0; c < values.cols; ++c) {
          const double grey = rng.gaussian(a);
          auto& v = values.at<cv::Vec3f>(r, c);
          for (int ch = 0; ch < 3; ++ch) v[ch] = static_cast<float>(grey + rng.gaussian(0.2 * a));
        }
      cv::Mat up;
      cv::resize(values, up, cv::Size(), factor, factor, cv::INTER_CUBIC);
      field += up(cv::Rect(factor, factor, gridSize.width, gridSize.height));
    }
    return field;
  };
  coarseNoise_ = sumOctaves(kCoarseOctaves);
  fineNoise_ = sumOctaves(kFineOctaves);

  // A colour of random lightness, mostly greyish, mixed towards the background by a random
  // amount so edges come at every contrast.
  auto randomColour = [&](double lowLum, double highLum) {
    const double lum = rng.uniform(lowLum, highLum);
    const double saturation = std::pow(rng.uniform(0.0, 1.0), 2.0);
    const double alpha = rng.uniform(0.25, 1.0);
    cv::Scalar c;
    for (int ch = 0; ch < 3; ++ch) {
      const double pure = std::clamp(lum + saturation * rng.uniform(-70.0, 70.0), 0.0, 255.0);
      c[ch] = style_.base[ch] + alpha * (pure - style_.base[ch]);
    }
    return c;
  };

  const double area = size_.width * size_.height;
  const int shapeCount = static_cast<int>(std::lround(style_.shapesPerSquareMetre * area));
  const double logMin = std::log(style_.minShapeMetres), logMax = std::log(style_.maxShapeMetres);
  for (int i = 0; i < shapeCount; ++i) {
    const double s = std::exp(rng.uniform(logMin, logMax));
    const cv::Point2d centre(rng.uniform(-0.5 * s, size_.width + 0.5 * s),
                             rng.uniform(-0.5 * s, size_.height + 0.5 * s));
    const double turn = rng.uniform(0.0, 2.0 * kPi);
    std::vector<cv::Point2d> local;
    switch (rng.uniform(0, 4)) {
      case 0: {  // rotated rectangle
        const double w = 0.5 * s, h = 0.5 * s * rng.uniform(0.25, 1.0);
        local = {{-w, -h}, {w, -h}, {w, h}, {-w, h}};
        break;
      }
      case 1:  // triangle
        for (int k = 0; k < 3; ++k) {
          const double a = k * 2.0 * kPi / 3.0 + rng.uniform(-0.6, 0.6);
          local.emplace_back(0.5 * s * std::cos(a), 0.5 * s * std::sin(a));
        }
        break;
      case 2: {  // irregular polygon, possibly concave
        const int n = rng.uniform(4, 9);
        for (int k = 0; k < n; ++k) {
          const double a = (k + rng.uniform(0.0, 0.8)) * 2.0 * kPi / n;
          const double r = 0.5 * s * rng.uniform(0.4, 1.0);
          local.emplace_back(r * std::cos(a), r * std::sin(a));
        }
        break;
      }
      default: {  // ellipse
        const double ry = rng.uniform(0.3, 1.0);
        for (int k = 0; k < 32; ++k) {
          const double a = k * 2.0 * kPi / 32;
          local.emplace_back(0.5 * s * std::cos(a), 0.5 * s * ry * std::sin(a));
        }
      }
    }
    Shape shape;
    for (const auto& p : local)
      shape.outline.emplace_back(centre.x + p.x * std::cos(turn) - p.y * std::sin(turn),
                                 centre.y + p.x * std::sin(turn) + p.y * std::cos(turn));
    shape.bounds = boundsOf(shape.outline);
    shape.colour = randomColour(10.0, 245.0);
    shape.strokeMetres = 0.0;
    shapes_.push_back(std::move(shape));
  }
  // Large shapes first so small details stay visible on top.
  std::stable_sort(shapes_.begin(), shapes_.end(), [](const Shape& a, const Shape& b) {
    return a.bounds.area() > b.bounds.area();
  });

  const int strokeCount = static_cast<int>(std::lround(style_.strokesPerSquareMetre * area));
  for (int i = 0; i < strokeCount; ++i) {
    Shape stroke;
    cv::Point2d p(rng.uniform(0.0, size_.width), rng.uniform(0.0, size_.height));
    double heading = rng.uniform(0.0, 2.0 * kPi);
    stroke.outline.push_back(p);
    const int segments = rng.uniform(2, 7);
    for (int k = 0; k < segments; ++k) {
      heading += rng.uniform(-1.5, 1.5);
      const double length = rng.uniform(0.01, 0.08);
      p += cv::Point2d(length * std::cos(heading), length * std::sin(heading));
      stroke.outline.push_back(p);
    }
    stroke.bounds = boundsOf(stroke.outline);
    stroke.colour = rng.uniform(0, 2) ? randomColour(0.0, 70.0) : randomColour(190.0, 255.0);
    stroke.strokeMetres = rng.uniform(0.0008, 0.004);
    shapes_.push_back(std::move(stroke));
  }
}

cv::Mat ProceduralTexture::sample(const cv::Mat& field, const cv::Rect2d& region,
                                  cv::Size pixels) const {
  // Texel (i, j) centre -> noise grid coordinates (grid sample k sits at k * kNoiseGridMetres).
  const double sx = region.width / pixels.width, sy = region.height / pixels.height;
  const cv::Matx23d toGrid(sx / kNoiseGridMetres, 0, (region.x + 0.5 * sx) / kNoiseGridMetres, 0,
                           sy / kNoiseGridMetres, (region.y + 0.5 * sy) / kNoiseGridMetres);
  cv::Mat out;
  cv::warpAffine(field, out, toGrid, pixels, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                 cv::BORDER_REFLECT101);
  return out;
}

cv::Mat ProceduralTexture::rasterize(const cv::Rect2d& region, cv::Size pixels) const {
  if (pixels.width <= 0 || pixels.height <= 0 || pixels.width > 16384 || pixels.height > 16384)
    throw Error("procedural texture: raster size must be within 1..16384 texels per side");
  if (!(region.width > 0.0 && region.height > 0.0))
    throw Error("procedural texture: region must have a positive size");

  // Draw on a canvas with a margin of kMarginTexels all round, then crop.
  const double texelX = region.width / pixels.width, texelY = region.height / pixels.height;
  const cv::Rect2d padded(region.x - kMarginTexels * texelX, region.y - kMarginTexels * texelY,
                          region.width + 2 * kMarginTexels * texelX,
                          region.height + 2 * kMarginTexels * texelY);
  const cv::Size paddedPixels(pixels.width + 2 * kMarginTexels, pixels.height + 2 * kMarginTexels);
  cv::Mat value(paddedPixels, CV_32FC3, style_.base);
  value += sample(coarseNoise_, padded, paddedPixels);
  cv::Mat canvas;
  value.convertTo(canvas, CV_8UC3);

  const double scaleX = 1.0 / texelX, scaleY = 1.0 / texelY;
  const double fixed = 1 << kShift;
  auto toPixels = [&](const std::vector<cv::Point2d>& outline) {
    std::vector<cv::Point> pts;
    for (const auto& p : outline)
      pts.emplace_back(static_cast<int>(std::lround(((p.x - padded.x) * scaleX - 0.5) * fixed)),
                       static_cast<int>(std::lround(((p.y - padded.y) * scaleY - 0.5) * fixed)));
    return pts;
  };
  for (const Shape& shape : shapes_) {
    const double pad = shape.strokeMetres;
    const cv::Rect2d reach(shape.bounds.x - pad, shape.bounds.y - pad, shape.bounds.width + 2 * pad,
                           shape.bounds.height + 2 * pad);
    if ((reach & padded).area() <= 0.0) continue;
    const std::vector<std::vector<cv::Point>> polys = {toPixels(shape.outline)};
    if (shape.strokeMetres == 0.0) {
      cv::fillPoly(canvas, polys, shape.colour, cv::LINE_AA, kShift);
    } else {
      const int thickness = std::max(1, static_cast<int>(std::lround(shape.strokeMetres * scaleX)));
      cv::polylines(canvas, polys, false, shape.colour, thickness, cv::LINE_AA, kShift);
    }
  }

  canvas.convertTo(value, CV_32FC3);
  value += sample(fineNoise_, padded, paddedPixels);
  cv::Mat out;
  value(cv::Rect(kMarginTexels, kMarginTexels, pixels.width, pixels.height))
      .convertTo(out, CV_8UC3);
  return out;
}

}  // namespace reftrack::app
