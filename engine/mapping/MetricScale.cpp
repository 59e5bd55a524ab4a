#include "engine/mapping/MetricScale.hpp"

#include <cmath>
#include <cstdio>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

constexpr double kMinPointSeparationPx = 10.0;

std::string number(double v, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace

MetricScale MetricScale::baseline(double metres) {
  MetricScale s;
  s.kind = Kind::Baseline;
  s.metres = metres;
  return s;
}

MetricScale MetricScale::distance(double metres, const cv::Point2d& first,
                                  const cv::Point2d& second) {
  MetricScale s;
  s.kind = Kind::Distance;
  s.metres = metres;
  s.first = first;
  s.second = second;
  return s;
}

void MetricScale::check(cv::Size imageSize) const {
  const char* what = kind == Kind::Baseline ? "the baseline" : "the distance";
  if (!std::isfinite(metres) || !(metres > 0.0))
    throw Error(std::string(what) + " must be a finite length in metres greater than 0, got " +
                std::to_string(metres));
  if (kind == Kind::Baseline) return;
  for (const cv::Point2d& p : {first, second})
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || p.x < 0 || p.y < 0 ||
        p.x > imageSize.width - 1 || p.y > imageSize.height - 1)
      throw Error("the distance's point (" + number(p.x, 1) + ", " + number(p.y, 1) +
                  ") lies outside the " + std::to_string(imageSize.width) + "x" +
                  std::to_string(imageSize.height) + " reference image");
  if (cv::norm(first - second) < kMinPointSeparationPx)
    throw Error("the distance's two points are " + number(cv::norm(first - second), 1) +
                " px apart (at least " + number(kMinPointSeparationPx, 0) +
                " needed): mark two points far apart on the scene's plane");
}

std::string MetricScale::toString() const {
  if (kind == Kind::Baseline) return "baseline " + number(metres, 4) + " m";
  return "distance " + number(metres, 4) + " m between (" + number(first.x, 1) + ", " +
         number(first.y, 1) + ") and (" + number(second.x, 1) + ", " + number(second.y, 1) +
         ") of the first reference";
}

}  // namespace reftrack
