#include "engine/homography/WarpedWindowSearch.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

// Offset of a parabola's vertex through (-1, a), (0, b), (1, c) from 0, within [-0.5, 0.5].
float vertexOffset(float a, float b, float c) {
  const float d = a - 2 * b + c;
  if (!(d < 0)) return 0.0f;
  const float o = 0.5f * (a - c) / d;
  return std::max(-0.5f, std::min(0.5f, o));
}

}  // namespace

std::vector<WindowMatch> searchWarpedWindows(const cv::Mat& frameGray, const NccPatches& windows,
                                             const std::vector<cv::Point2f>& predicted, int radius,
                                             double minScore) {
  if (frameGray.empty() || frameGray.type() != CV_8UC1)
    throw Error("warped window search: the frame must be a non-empty 8-bit grey image");
  if (static_cast<int>(predicted.size()) != windows.size())
    throw Error("warped window search: one predicted position per window is required");
  if (radius < 1) throw Error("warped window search: radius must be at least 1");
  const int h = windows.halfWindow(), side = 2 * h + 1, reach = radius + h;
  cv::Mat frame;
  frameGray.convertTo(frame, CV_32F);
  std::vector<WindowMatch> out;
  cv::Mat response;
  for (int i = 0; i < windows.size(); ++i) {
    if (!windows.valid(i)) continue;
    const cv::Point2f q = predicted[static_cast<size_t>(i)];
    if (!std::isfinite(q.x) || !std::isfinite(q.y)) continue;
    const int cx = static_cast<int>(std::lround(q.x)), cy = static_cast<int>(std::lround(q.y));
    if (cx - reach < 0 || cy - reach < 0 || cx + reach >= frame.cols || cy + reach >= frame.rows)
      continue;
    const cv::Mat templ(side, side, CV_32F, const_cast<float*>(windows.patch(i)));
    cv::matchTemplate(frame(cv::Rect(cx - reach, cy - reach, 2 * reach + 1, 2 * reach + 1)), templ,
                      response, cv::TM_CCOEFF_NORMED);
    double best = 0;
    cv::Point at;
    cv::minMaxLoc(response, nullptr, &best, nullptr, &at);
    if (best < minScore || at.x == 0 || at.y == 0 || at.x == response.cols - 1 ||
        at.y == response.rows - 1)
      continue;
    const float* row = response.ptr<float>(at.y);
    const float dx = vertexOffset(row[at.x - 1], row[at.x], row[at.x + 1]);
    const float dy = vertexOffset(response.at<float>(at.y - 1, at.x), row[at.x],
                                  response.at<float>(at.y + 1, at.x));
    out.push_back({i,
                   cv::Point2f(static_cast<float>(cx - radius + at.x) + dx,
                               static_cast<float>(cy - radius + at.y) + dy),
                   static_cast<float>(best)});
  }
  return out;
}

}  // namespace reftrack
