#pragma once
// PlotCanvas: a fixed-size 2D chart drawn with OpenCV — line and scatter series with colours and
// labels, axes with tick labels, a title and a legend — saved as PNG (atomically). Axis ranges
// cover all series with a 5% margin; equalAspect keeps one data unit the same length on both axes
// (for top views of trajectories).
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace reftrack::app {

class PlotCanvas {
 public:
  explicit PlotCanvas(std::string title, std::string xLabel = "", std::string yLabel = "",
                      cv::Size size = {900, 600});

  // x and y must have the same length (throws reftrack::Error otherwise); non-finite points are
  // skipped (a line breaks there). Colours are BGR.
  void addLine(const std::string& label, const std::vector<double>& x, const std::vector<double>& y,
               const cv::Scalar& colour);
  void addScatter(const std::string& label, const std::vector<double>& x,
                  const std::vector<double>& y, const cv::Scalar& colour);
  void setEqualAspect(bool equal) { equalAspect_ = equal; }

  cv::Mat render() const;                             // CV_8UC3 of the canvas size
  void save(const std::filesystem::path& png) const;  // atomic; throws reftrack::Error
  // Where the data point (x, y) lands in render()'s image (for tests and annotations).
  cv::Point2d toPixel(double x, double y) const;

 private:
  struct Series {
    std::string label;
    std::vector<double> x, y;
    cv::Scalar colour;
    bool line = true;
  };
  struct Frame {
    cv::Rect area;
    double x0, x1, y0, y1;
  };
  Frame layout() const;
  void add(const std::string& label, const std::vector<double>& x, const std::vector<double>& y,
           const cv::Scalar& colour, bool line);

  std::string title_, xLabel_, yLabel_;
  cv::Size size_;
  bool equalAspect_ = false;
  std::vector<Series> series_;
};

}  // namespace reftrack::app
