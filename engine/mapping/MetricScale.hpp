#pragma once
// MetricScale: the one distance a user knows that gives a map of an unprepared scene its metres
// (two views fix everything but the scale). Either the baseline — how far the camera moved
// between the two references (a tape measure, a ruler along the desk's edge, a known step) — or
// the distance between two points of the scene's dominant plane marked in the first reference's
// image (two corners of a sheet of paper, the ends of a ruler on the desk).
#include <opencv2/core.hpp>
#include <string>

namespace reftrack {

struct MetricScale {
  enum class Kind { Baseline, Distance };
  Kind kind = Kind::Baseline;
  double metres = 0.0;
  // Distance: the two points as pixels of the first reference (as recorded: lens included).
  cv::Point2d first, second;

  static MetricScale baseline(double metres);
  static MetricScale distance(double metres, const cv::Point2d& first, const cv::Point2d& second);

  // Throws reftrack::Error naming what is wrong: a length that is not a finite positive number of
  // metres, a point outside an image of `imageSize` or two points closer than 10 pixels.
  void check(cv::Size imageSize) const;
  // "baseline 0.04 m" or "distance 0.297 m between (102.0, 330.5) and (410.0, 325.0) of the
  // first reference".
  std::string toString() const;
};

}  // namespace reftrack
