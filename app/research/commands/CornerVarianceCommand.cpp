// `reftrack corner-variance`: the paper's Fig. 7 with this project's corner
// detector — prints the table (contrast, detection rate, position variance) and
// the fitted variance curve, and writes the plot as a PNG.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "app/commands/Commands.hpp"
#include "app/plot/PlotCanvas.hpp"
#include "app/research/corners/CornerAccuracyExperiment.hpp"

namespace reftrack::app {

namespace {

CommandRegistration registerCornerVarianceCommand(CLI::App& parent) {
  CLI::App* sub = parent.add_subcommand(
      "corner-variance", "Paper Fig. 7: corner position variance against RMS contrast");
  struct Options {
    CornerAccuracyOptions experiment;
    std::filesystem::path plot = "corner_variance.png";
  };
  auto o = std::make_shared<Options>();
  sub->add_option("--trials", o->experiment.trialsPerAmplitude, "Trials per contrast step")
      ->check(CLI::Range(10, 100000));
  sub->add_option("--noise", o->experiment.noiseSigma, "Noise SD (grey levels)")
      ->check(CLI::Range(0.0, 100.0));
  sub->add_option("--seed", o->experiment.seed, "Random seed");
  sub->add_option("--plot", o->plot, "Output PNG plot");
  return {sub, [o] {
            const CornerAccuracyResult r = runCornerAccuracyExperiment(o->experiment);
            std::printf("%10s %14s %10s %14s %10s %14s\n", "amplitude", "rms_contrast", "detected",
                        "variance_px2", "bias_px", "fitted_px2");
            std::vector<double> mx, my, fx, fy;
            for (const CornerAccuracyRow& row : r.rows) {
              std::printf("%10.1f %14.2f %10.3f %14.5f %10.4f %14.5f\n", row.amplitude,
                          row.rmsContrast, row.detectionRate, row.variancePx2, row.biasPx,
                          r.fitted.variance(row.rmsContrast));
              if (row.detectionRate > 0.5) {
                mx.push_back(row.rmsContrast);
                my.push_back(row.variancePx2);
              }
              fx.push_back(row.rmsContrast);
              fy.push_back(r.fitted.variance(row.rmsContrast));
            }
            std::printf("fit: variance(c) = %.5f + %.3f / c^2  px^2 (floor SD %.3f px)\n",
                        r.fitted.floorPx2, r.fitted.scalePx2, std::sqrt(r.fitted.floorPx2));
            PlotCanvas plot("Corner position variance vs RMS contrast (noise SD " +
                                std::to_string(static_cast<int>(o->experiment.noiseSigma)) + ")",
                            "RMS contrast of the 15x15 window (grey levels)",
                            "position variance (px^2)");
            plot.addScatter("measured variance", mx, my, cv::Scalar(200, 80, 0));
            plot.addLine("fit: floor + scale / c^2", fx, fy, cv::Scalar(0, 0, 200));
            plot.save(o->plot);
            std::printf("plot: %s\n", o->plot.string().c_str());
          }};
}

const CommandRegistrar registrar(70, registerCornerVarianceCommand, CommandGroup::Research);

}  // namespace

}  // namespace reftrack::app
