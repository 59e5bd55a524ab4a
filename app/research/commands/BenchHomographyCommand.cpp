// `reftrack bench-homography`: homography mode against the baseline users reach for today (ORB
// 1000 features + brute-force Hamming with cross-check + findHomography RANSAC) on the very same
// simulated pure-rotation frames, single thread, at one or more sizes: per-frame median
// milliseconds, median and mean registration error at the frame corners, and their ratios.
#include <cmath>
#include <cstdio>
#include <memory>
#include <opencv2/core/utility.hpp>
#include <sstream>

#include "app/cli/ImageSizeValidator.hpp"
#include "app/commands/Commands.hpp"
#include "app/research/homography/HomographyBenchmark.hpp"
#include "app/simulator/SimulationOptions.hpp"
#include "engine/core/Error.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {

namespace {

struct BenchArgs {
  std::vector<std::string> sizes{"320x240", "640x480"};
  int frames = 150;
  double noise = 2.0;
  std::uint64_t seed = 1;
  std::filesystem::path params;
};

double finiteMean(const std::vector<double>& values) {
  double sum = 0;
  int n = 0;
  for (double v : values)
    if (std::isfinite(v)) {
      sum += v;
      ++n;
    }
  return n > 0 ? sum / n : NAN;
}

void printSide(const BenchmarkSide& s, int frames) {
  for (std::size_t i = 0; i < std::min<std::size_t>(5, s.failures.size()); ++i)
    std::fprintf(stderr, "%s not registered: %s\n", s.name.c_str(), s.failures[i].c_str());
  std::printf("  %-24s %5d/%-5d %9.3f %12.3f %12.3f\n", s.name.c_str(), s.registered, frames,
              finiteMedian(s.milliseconds), finiteMedian(s.cornerErrorPx),
              finiteMean(s.cornerErrorPx));
}

CommandRegistration registerBenchHomographyCommand(CLI::App& parent) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* sub = parent.add_subcommand(
      "bench-homography", "Homography mode vs ORB + findHomography on the same frames (speed)");
  sub->add_option("--sizes", args->sizes, "Image sizes WIDTHxHEIGHT")
      ->check(imageSizeValidator())
      ->capture_default_str();
  sub->add_option("--frames", args->frames, "Frames per size")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--noise", args->noise, "Sensor noise SD (grey levels)")
      ->check(CLI::Range(0.0, 50.0))
      ->capture_default_str();
  sub->add_option("--seed", args->seed, "Sensor noise seed")->capture_default_str();
  sub->add_option("--params", args->params, "TrackerParams YAML")->check(CLI::ExistingFile);
  sub->footer(
      "Frames: the simulator's 'rotate' preset (60 degree field of view, pan +-40 degrees about\n"
      "reference view A's optical centre), so each frame's true homography K R K^-1 is exact.\n"
      "Error: mean over the frame's 4 corners of |H_est H_true^-1 c - c| (px). Times cover the\n"
      "registration call on a grey frame as thread CPU time, one thread (cv::setNumThreads(1)).");
  return {
      sub, [args] {
        cv::setNumThreads(1);
        const TrackerParams params =
            args->params.empty() ? TrackerParams{} : TrackerParams::load(args->params);
        const auto context = render::createHeadlessContext();
        std::vector<BenchmarkResult> results;
        for (const std::string& text : args->sizes) {
          BenchmarkOptions o;
          o.size = *parseImageSize(text);
          o.frames = args->frames;
          o.noiseSigma = args->noise;
          o.seed = args->seed;
          o.params = params;
          results.push_back(runHomographyBenchmark(o));
        }
        std::printf("%-26s %11s %9s %12s %12s\n", "  method", "registered", "cpu_ms_med",
                    "err_median", "err_mean");
        for (const BenchmarkResult& r : results) {
          std::printf("%dx%d, %d frames\n", r.size.width, r.size.height, r.frames);
          printSide(r.tracker, r.frames);
          printSide(r.baseline, r.frames);
          printSide(r.calibratedTracker, r.frames);
          std::printf("  %s stage medians (ms):", r.tracker.name.c_str());
          for (const auto& [stage, ms] : r.tracker.stageMs)
            std::printf(" %s %.3f;", stage.c_str(), finiteMedian(ms));
          std::printf("\n");
          const double speed =
              finiteMedian(r.baseline.milliseconds) / finiteMedian(r.tracker.milliseconds);
          const double accuracy =
              finiteMedian(r.baseline.cornerErrorPx) / finiteMedian(r.tracker.cornerErrorPx);
          std::printf(
              "  speed-up (baseline / reftrack median ms): %.1fx;"
              " error ratio (baseline / reftrack median): %.2f\n",
              speed, accuracy);
          std::printf(
              "  given K (rotation model): %.2fx the time of the tracker without K, error "
              "ratio (without / with K median): %.2f\n",
              finiteMedian(r.calibratedTracker.milliseconds) / finiteMedian(r.tracker.milliseconds),
              finiteMedian(r.tracker.cornerErrorPx) /
                  finiteMedian(r.calibratedTracker.cornerErrorPx));
        }
      }};
}

const CommandRegistrar registrar(85, registerBenchHomographyCommand, CommandGroup::Research);

}  // namespace

}  // namespace reftrack::app
