#include "app/research/sixdof/SixDofPlots.hpp"

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/plot/PlotCanvas.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {
const cv::Scalar kColours[] = {{200, 90, 20}, {30, 30, 210}, {40, 160, 40}, {150, 40, 150}};
}

void writeCubeErrorPlot(const SimulatedSequence& s, const std::vector<const TrackerRun*>& runs,
                        const std::filesystem::path& png) {
  PlotCanvas plot("Virtual cube vertex error, " + s.options.preset + " (" +
                      std::to_string(s.frames.size()) + " frames)",
                  "frame", "mean vertex error (px)");
  std::size_t c = 0;
  for (const TrackerRun* run : runs) {
    std::vector<double> x, y;
    for (const FrameEvaluation& f : run->evaluation.frames)
      if (f.cubeErrorPx) {
        x.push_back(f.timestamp * s.options.fps);
        y.push_back(*f.cubeErrorPx);
      }
    plot.addLine(run->name, x, y, kColours[c++ % 4]);
  }
  plot.save(png);
}

void writeMotionComponentsPlot(const SimulatedSequence& s, const TrackerRun& standard,
                               const TrackerRun& regularised, const std::filesystem::path& png) {
  // Paper Fig. 13: each motion component of x_Ak over the frames, standard vs regularised, one
  // panel per component stacked into one PNG.
  const char* names[6] = {"t_x (mm)",  "t_y (mm)",  "t_z (mm)",
                          "r_x (deg)", "r_y (deg)", "r_z (deg)"};
  std::vector<cv::Mat> panels;
  for (int i = 0; i < 6; ++i) {
    PlotCanvas plot(std::string("x_Ak component ") + names[i] + ", " + s.options.preset, "frame",
                    names[i], cv::Size(900, 260));
    const double scale = i < 3 ? 1000.0 : 180.0 / CV_PI;
    for (const TrackerRun* run : {&standard, &regularised}) {
      std::vector<double> x, y;
      for (std::size_t k = 0; k < run->motion.size(); ++k)
        if (run->motion[k]) {
          x.push_back(static_cast<double>(k));
          y.push_back((*run->motion[k])[i] * scale);
        }
      plot.addLine(run->name, x, y, run == &standard ? kColours[0] : kColours[1]);
    }
    panels.push_back(plot.render());
  }
  cv::Mat all;
  cv::vconcat(panels, all);
  writeFileAtomically(png, [&](const std::filesystem::path& tmp) {
    if (!cv::imwrite(tmp.string(), all)) throw Error("cannot write " + png.string());
  });
}

}  // namespace reftrack::app
