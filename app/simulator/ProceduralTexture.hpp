#pragma once
// ProceduralTexture: a seeded, non-repetitive colour texture over a rectangular surface of given
// size in metres — multi-octave value noise, overlapping rotated rectangles, triangles, polygons
// and ellipses of varied grey/colour and contrast, and random pen strokes. Never a regular grid,
// so correlation matching has no aliases. Any sub-rectangle can be rasterised at any resolution;
// neighbouring tiles rasterised at the same resolution join without seams.
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack::app {

struct TextureStyle {
  cv::Scalar base{150, 160, 170};                        // BGR background level
  double shapesPerSquareMetre = 700.0;                   // covers the surface about 1.5 times
  double minShapeMetres = 0.004, maxShapeMetres = 0.08;  // log-uniform sizes
  double strokesPerSquareMetre = 120.0;
  double noiseAmplitude = 1.0;  // scales the value-noise octaves
  void check() const;           // throws reftrack::Error naming the bad field
};

class ProceduralTexture {
 public:
  ProceduralTexture(std::uint64_t seed, cv::Size2d surfaceMetres, TextureStyle style = {});

  // BGR (CV_8UC3) image of `region` (metres; surface origin top-left, x right, y down) with
  // `pixels` texels; texel (i, j) samples the surface at the centre of its footprint.
  cv::Mat rasterize(const cv::Rect2d& region, cv::Size pixels) const;

  cv::Size2d surfaceMetres() const { return size_; }

 private:
  struct Shape {
    std::vector<cv::Point2d> outline;  // metres, closed polygon
    cv::Rect2d bounds;
    cv::Scalar colour;
    double strokeMetres;  // 0: filled; else an open polyline of this width
  };
  // `field` resampled (bilinear) at the texel centres of `region`.
  cv::Mat sample(const cv::Mat& field, const cv::Rect2d& region, cv::Size pixels) const;

  cv::Size2d size_;
  TextureStyle style_;
  // Value noise summed over octaves on a 2 mm grid (CV_32FC3): the coarse octaves shade the
  // background, the fine ones overlay everything, shapes included.
  cv::Mat coarseNoise_, fineNoise_;
  std::vector<Shape> shapes_;  // large first, strokes last
};

}  // namespace reftrack::app
