// Annotations: everything becomes pixel-space triangles in one PixelCanvas; text comes from
// stb_easy_font's quads.
#include "render/Annotations2D.hpp"

#include <stb/stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "engine/core/Error.hpp"

namespace reftrack::render {

namespace {

Eigen::Vector2f vec(const cv::Point2f& p) { return {p.x, p.y}; }

void checkPoint(const cv::Point2f& p, const char* what) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    throw Error(std::string("annotation ") + what + " has a non-finite coordinate");
}

void checkPositive(float value, const char* what) {
  if (!std::isfinite(value) || !(value > 0))
    throw Error(std::string("annotation ") + what + " must be positive");
}

// stb_easy_font takes mutable char buffers.
std::vector<char> mutableText(const std::string& text) {
  std::vector<char> buffer(text.begin(), text.end());
  buffer.push_back('\0');
  return buffer;
}

constexpr float kBoxPadding = 2.0f;  // in glyph units (scaled with the text)

}  // namespace

std::optional<std::pair<cv::Point2d, cv::Point2d>> clipLineToImage(double a, double b, double c,
                                                                   cv::Size imageSize) {
  if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c))
    throw Error("line coefficients must be finite");
  if (a == 0 && b == 0) return std::nullopt;
  const double x0 = -0.5, y0 = -0.5, x1 = imageSize.width - 0.5, y1 = imageSize.height - 0.5;
  std::vector<cv::Point2d> hits;
  const double eps = 1e-9 * std::max({1.0, x1, y1});
  auto inside = [&](const cv::Point2d& p) {
    return p.x >= x0 - eps && p.x <= x1 + eps && p.y >= y0 - eps && p.y <= y1 + eps;
  };
  if (b != 0)
    for (double x : {x0, x1}) {
      const cv::Point2d p(x, -(a * x + c) / b);
      if (inside(p)) hits.push_back(p);
    }
  if (a != 0)
    for (double y : {y0, y1}) {
      const cv::Point2d p(-(b * y + c) / a, y);
      if (inside(p)) hits.push_back(p);
    }
  if (hits.size() < 2) return std::nullopt;
  // The two hits farthest apart (a line through a corner hits two borders at the same point).
  std::pair<cv::Point2d, cv::Point2d> best{hits[0], hits[0]};
  double bestDistance = -1;
  for (size_t i = 0; i < hits.size(); ++i)
    for (size_t j = i + 1; j < hits.size(); ++j)
      if (cv::norm(hits[i] - hits[j]) > bestDistance) {
        bestDistance = cv::norm(hits[i] - hits[j]);
        best = {hits[i], hits[j]};
      }
  return best;
}

cv::Rect2f Annotations2D::textBox(const cv::Point2f& topLeft, const std::string& text,
                                  float scale) {
  std::vector<char> buffer = mutableText(text);
  const float width = static_cast<float>(stb_easy_font_width(buffer.data())) * scale;
  const float height = static_cast<float>(stb_easy_font_height(buffer.data())) * scale;
  const float pad = kBoxPadding * scale;
  return {topLeft.x - 0.5f - pad, topLeft.y - 0.5f - pad, width + 2 * pad, height + pad};
}

void Annotations2D::addText(const cv::Point2f& topLeft, const std::string& text,
                            const cv::Scalar& colourBgr, float scale, bool box) {
  checkPoint(topLeft, "text position");
  checkPositive(scale, "text scale");
  if (text.empty()) return;
  if (box) {
    const cv::Rect2f r = textBox(topLeft, text, scale);
    canvas_.addQuad({r.x, r.y}, {r.x + r.width, r.y}, {r.x + r.width, r.y + r.height},
                    {r.x, r.y + r.height}, Eigen::Vector4f(0.0f, 0.0f, 0.0f, 0.65f));
  }
  std::vector<char> buffer = mutableText(text);
  // About 270 bytes of vertices per character is stb_easy_font's documented worst case.
  std::vector<char> vertices(buffer.size() * 300 + 1024);
  const int quads = stb_easy_font_print(0, 0, buffer.data(), nullptr, vertices.data(),
                                        static_cast<int>(vertices.size()));
  const Eigen::Vector4f rgba = rgbaFromBgr(colourBgr);
  // Glyph quads have integer corners; shifting by -0.5 puts them on pixel edges.
  const Eigen::Vector2f origin(topLeft.x - 0.5f, topLeft.y - 0.5f);
  for (int q = 0; q < quads; ++q) {
    Eigen::Vector2f corner[4];
    for (int k = 0; k < 4; ++k) {
      float xy[2];
      std::memcpy(xy, vertices.data() + (4 * q + k) * 16, sizeof xy);  // x, y, z, rgba bytes
      corner[k] = origin + scale * Eigen::Vector2f(xy[0], xy[1]);
    }
    canvas_.addQuad(corner[0], corner[1], corner[2], corner[3], rgba);
  }
}

void Annotations2D::addDot(const cv::Point2f& centre, float radius, const cv::Scalar& colourBgr) {
  checkPoint(centre, "dot");
  checkPositive(radius, "dot radius");
  canvas_.addDisc(vec(centre), radius, rgbaFromBgr(colourBgr));
}

void Annotations2D::addSegment(const cv::Point2f& from, const cv::Point2f& to, float thickness,
                               const cv::Scalar& colourBgr) {
  checkPoint(from, "segment");
  checkPoint(to, "segment");
  checkPositive(thickness, "segment thickness");
  canvas_.addThickLine(vec(from), vec(to), thickness, rgbaFromBgr(colourBgr));
}

bool Annotations2D::addInfiniteLine(double a, double b, double c, cv::Size imageSize,
                                    float thickness, const cv::Scalar& colourBgr) {
  const auto clipped = clipLineToImage(a, b, c, imageSize);
  if (!clipped) return false;
  addSegment(clipped->first, clipped->second, thickness, colourBgr);
  return true;
}

void Annotations2D::addPolyline(const std::vector<cv::Point2f>& points, bool closed,
                                float thickness, const cv::Scalar& colourBgr) {
  checkPositive(thickness, "polyline thickness");
  for (const cv::Point2f& p : points) checkPoint(p, "polyline");
  for (size_t i = 0; i + 1 < points.size(); ++i)
    addSegment(points[i], points[i + 1], thickness, colourBgr);
  if (closed && points.size() > 2) addSegment(points.back(), points.front(), thickness, colourBgr);
}

void Annotations2D::clear() { canvas_.clear(); }

void Annotations2D::draw(cv::Size imageSize) { canvas_.draw(imageSize); }

}  // namespace reftrack::render
