#include "app/plot/PlotCanvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

const int kFont = cv::FONT_HERSHEY_SIMPLEX;

// Tick spacing of 1, 2 or 5 times a power of ten giving about `target` ticks.
double niceStep(double range, int target) {
  const double raw = range / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * mag >= raw) return m * mag;
  return 10.0 * mag;
}

std::string tickText(double v, double step) {
  char buf[32];
  if (std::abs(v) < step * 1e-6) v = 0.0;
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

PlotCanvas::PlotCanvas(std::string title, std::string xLabel, std::string yLabel, cv::Size size)
    : title_(std::move(title)),
      xLabel_(std::move(xLabel)),
      yLabel_(std::move(yLabel)),
      size_(size) {
  if (size.width < 200 || size.height < 150)
    throw Error("plot size must be at least 200x150 pixels");
}

void PlotCanvas::add(const std::string& label, const std::vector<double>& x,
                     const std::vector<double>& y, const cv::Scalar& colour, bool line) {
  if (x.size() != y.size())
    throw Error("plot series '" + label + "': x has " + std::to_string(x.size()) +
                " values but y has " + std::to_string(y.size()));
  series_.push_back({label, x, y, colour, line});
}

void PlotCanvas::addLine(const std::string& label, const std::vector<double>& x,
                         const std::vector<double>& y, const cv::Scalar& colour) {
  add(label, x, y, colour, true);
}

void PlotCanvas::addScatter(const std::string& label, const std::vector<double>& x,
                            const std::vector<double>& y, const cv::Scalar& colour) {
  add(label, x, y, colour, false);
}

PlotCanvas::Frame PlotCanvas::layout() const {
  Frame f;
  f.area = cv::Rect(80, 50, size_.width - 80 - 30, size_.height - 50 - 60);
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const Series& s : series_)
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        x0 = std::min(x0, s.x[i]), x1 = std::max(x1, s.x[i]);
        y0 = std::min(y0, s.y[i]), y1 = std::max(y1, s.y[i]);
      }
  if (!std::isfinite(x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  auto widen = [](double& lo, double& hi) {
    double span = hi - lo;
    if (span <= 0) span = std::max(1e-9, std::abs(lo) * 0.1 + 1e-9), lo -= span / 2, hi += span / 2;
    lo -= 0.05 * (hi - lo);
    hi += 0.05 * (hi - lo) / 1.05;
  };
  widen(x0, x1);
  widen(y0, y1);
  if (equalAspect_) {
    const double sx = (x1 - x0) / f.area.width, sy = (y1 - y0) / f.area.height;
    const double s = std::max(sx, sy);
    const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
    x0 = cx - 0.5 * s * f.area.width, x1 = cx + 0.5 * s * f.area.width;
    y0 = cy - 0.5 * s * f.area.height, y1 = cy + 0.5 * s * f.area.height;
  }
  f.x0 = x0, f.x1 = x1, f.y0 = y0, f.y1 = y1;
  return f;
}

cv::Point2d PlotCanvas::toPixel(double x, double y) const {
  const Frame f = layout();
  return {f.area.x + (x - f.x0) / (f.x1 - f.x0) * f.area.width,
          f.area.y + f.area.height - (y - f.y0) / (f.y1 - f.y0) * f.area.height};
}

cv::Mat PlotCanvas::render() const {
  cv::Mat img(size_, CV_8UC3, cv::Scalar(255, 255, 255));
  const Frame f = layout();
  const cv::Scalar black(0, 0, 0), grid(225, 225, 225);
  auto px = [&](double x, double y) {
    return cv::Point2d(f.area.x + (x - f.x0) / (f.x1 - f.x0) * f.area.width,
                       f.area.y + f.area.height - (y - f.y0) / (f.y1 - f.y0) * f.area.height);
  };
  // Grid and tick labels.
  const double xs = niceStep(f.x1 - f.x0, 8), ys = niceStep(f.y1 - f.y0, 6);
  for (double x = std::ceil(f.x0 / xs) * xs; x <= f.x1; x += xs) {
    const int u = cvRound(px(x, f.y0).x);
    cv::line(img, {u, f.area.y}, {u, f.area.y + f.area.height}, grid, 1);
    const std::string t = tickText(x, xs);
    const cv::Size ts = cv::getTextSize(t, kFont, 0.4, 1, nullptr);
    cv::putText(img, t, {u - ts.width / 2, f.area.y + f.area.height + 16}, kFont, 0.4, black, 1,
                cv::LINE_AA);
  }
  for (double y = std::ceil(f.y0 / ys) * ys; y <= f.y1; y += ys) {
    const int v = cvRound(px(f.x0, y).y);
    cv::line(img, {f.area.x, v}, {f.area.x + f.area.width, v}, grid, 1);
    const std::string t = tickText(y, ys);
    const cv::Size ts = cv::getTextSize(t, kFont, 0.4, 1, nullptr);
    cv::putText(img, t, {f.area.x - ts.width - 6, v + 4}, kFont, 0.4, black, 1, cv::LINE_AA);
  }
  cv::rectangle(img, f.area, black, 1);
  // Series, clipped to the plot area.
  cv::Mat plotArea = img(f.area);
  const cv::Point2d origin(f.area.x, f.area.y);
  const int shift = 4;  // sub-pixel drawing: 4 fractional bits
  auto fixed = [&](const cv::Point2d& p) {
    return cv::Point(cvRound((p.x - origin.x) * (1 << shift)),
                     cvRound((p.y - origin.y) * (1 << shift)));
  };
  for (const Series& s : series_) {
    bool havePrev = false;
    cv::Point2d prev;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
        havePrev = false;
        continue;
      }
      const cv::Point2d p = px(s.x[i], s.y[i]);
      if (s.line) {
        if (havePrev) cv::line(plotArea, fixed(prev), fixed(p), s.colour, 2, cv::LINE_AA, shift);
      } else {
        cv::circle(plotArea, fixed(p), 3 << shift, s.colour, cv::FILLED, cv::LINE_AA, shift);
      }
      prev = p;
      havePrev = true;
    }
  }
  // Title, axis labels, legend.
  const cv::Size tt = cv::getTextSize(title_, kFont, 0.7, 2, nullptr);
  cv::putText(img, title_, {(size_.width - tt.width) / 2, 32}, kFont, 0.7, black, 2, cv::LINE_AA);
  const cv::Size xt = cv::getTextSize(xLabel_, kFont, 0.5, 1, nullptr);
  cv::putText(img, xLabel_, {f.area.x + (f.area.width - xt.width) / 2, size_.height - 14}, kFont,
              0.5, black, 1, cv::LINE_AA);
  if (!yLabel_.empty()) {
    const cv::Size yt = cv::getTextSize(yLabel_, kFont, 0.5, 1, nullptr);
    cv::Mat label(yt.height + 8, yt.width + 4, CV_8UC3, cv::Scalar(255, 255, 255));
    cv::putText(label, yLabel_, {2, yt.height + 2}, kFont, 0.5, black, 1, cv::LINE_AA);
    cv::rotate(label, label, cv::ROTATE_90_COUNTERCLOCKWISE);
    const int top = std::max(0, f.area.y + (f.area.height - label.rows) / 2);
    if (label.rows <= size_.height - top && label.cols <= 20)
      label.copyTo(img(cv::Rect(4, top, label.cols, label.rows)));
  }
  int row = 0;
  for (const Series& s : series_) {
    if (s.label.empty()) continue;
    const cv::Size ls = cv::getTextSize(s.label, kFont, 0.45, 1, nullptr);
    const int x = f.area.x + f.area.width - ls.width - 40, y = f.area.y + 18 + 18 * row++;
    cv::rectangle(img, {x - 30, y - 12}, {x + ls.width + 6, y + 5}, cv::Scalar(255, 255, 255),
                  cv::FILLED);
    if (s.line)
      cv::line(img, {x - 26, y - 4}, {x - 6, y - 4}, s.colour, 2, cv::LINE_AA);
    else
      cv::circle(img, {x - 16, y - 4}, 3, s.colour, cv::FILLED, cv::LINE_AA);
    cv::putText(img, s.label, {x, y}, kFont, 0.45, black, 1, cv::LINE_AA);
  }
  return img;
}

void PlotCanvas::save(const std::filesystem::path& png) const {
  const cv::Mat img = render();
  writeFileAtomically(png, [&](const std::filesystem::path& tmp) {
    bool ok = false;
    try {
      ok = cv::imwrite(tmp.string(), img);
    } catch (const cv::Exception& e) {
      throw Error("cannot write plot '" + png.string() + "': " + e.err);
    }
    if (!ok) throw Error("cannot write plot '" + png.string() + "' (is the extension .png?)");
  });
}

}  // namespace reftrack::app
