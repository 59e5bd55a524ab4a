#include "app/research/homography/HomographyPairsExperiment.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "app/cli/ProgressBar.hpp"
#include "app/research/baselines/OpenCvFeatureBaseline.hpp"
#include "app/research/homography/HardHomographyPairs.hpp"
#include "app/research/homography/HomographyGroundTruth.hpp"
#include "app/simulator/SensorNoise.hpp"  // mixSeed
#include "engine/core/Error.hpp"
#include "engine/core/ThreadCpuClock.hpp"
#include "engine/homography/HomographyTracker.hpp"

namespace reftrack::app {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Synthesised views of img1 per sequence: out-of-plane tilts about a horizontal and a vertical
// axis (and one diagonal), and zoom + in-plane rotation (the last two beyond issue 13's 0.5-2x,
// like the Oxford boat / bark pairs, which zoom to ~4x).
struct ViewSpec {
  const char* kind;
  double tiltDeg, azimuthDeg, scale, rollDeg;
};
constexpr ViewSpec kViews[] = {
    {"viewpoint", 20, 0, 1, 0},        {"viewpoint", 30, 90, 1, 0},
    {"viewpoint", 40, 0, 1, 0},        {"viewpoint", 50, 90, 1, 0},
    {"viewpoint", 60, 0, 1, 0},        {"viewpoint", 20, 90, 1, 0},
    {"viewpoint", 30, 0, 1, 0},        {"viewpoint", 40, 90, 1, 0},
    {"viewpoint", 50, 45, 1, 0},       {"viewpoint", 60, 90, 1, 0},
    {"zoom-rotation", 0, 0, 0.5, 45},  {"zoom-rotation", 0, 0, 0.7, 120},
    {"zoom-rotation", 0, 0, 1.4, 200}, {"zoom-rotation", 0, 0, 2.0, 300},
    {"zoom-rotation", 0, 0, 0.6, 270}, {"zoom-rotation", 0, 0, 1.7, 90},
    {"zoom-rotation", 0, 0, 2.8, 150}, {"zoom-rotation", 0, 0, 3.5, 60},
};

cv::Matx33d readHomography(const std::filesystem::path& file) {
  cv::FileStorage fs(file.string(), cv::FileStorage::READ);
  cv::Mat H;
  if (fs.isOpened()) fs.getFirstTopLevelNode() >> H;
  if (H.rows != 3 || H.cols != 3)
    throw Error("pairs: cannot read a 3x3 homography from " + file.string());
  H.convertTo(H, CV_64F);
  return cv::Matx33d(H);
}

// Thread CPU time of f (what one core spends on it, whatever else the machine runs).
template <class F>
double timedMs(F&& f) {
  const double t0 = threadCpuMs();
  f();
  return threadCpuMs() - t0;
}

}  // namespace

std::vector<HomographyPair> buildHomographyPairs(const std::filesystem::path& dataDir,
                                                 double noiseSigma, std::uint64_t seed) {
  if (!std::filesystem::is_directory(dataDir))
    throw Error("pairs: " + dataDir.string() + " is not a folder");
  std::vector<std::filesystem::path> sequences;
  for (const auto& e : std::filesystem::directory_iterator(dataDir))
    if (e.is_directory() && std::filesystem::exists(e.path() / "img1.png"))
      sequences.push_back(e.path());
  std::sort(sequences.begin(), sequences.end());
  if (sequences.empty())
    throw Error("pairs: no sequence folder with img1.png under " + dataDir.string());
  std::vector<HomographyPair> out;
  std::uint64_t n = 0;
  for (const auto& dir : sequences) {
    const std::string name = dir.filename().string();
    const cv::Mat reference = cv::imread((dir / "img1.png").string(), cv::IMREAD_GRAYSCALE);
    if (reference.empty()) throw Error("pairs: cannot read " + (dir / "img1.png").string());
    for (int k = 2; k <= 6; ++k) {
      const auto img = dir / ("img" + std::to_string(k) + ".png");
      const auto hf = dir / ("H1to" + std::to_string(k) + "p.xml");
      if (!std::filesystem::exists(img) || !std::filesystem::exists(hf)) continue;
      HomographyPair p{name,
                       "photometric",
                       "1->" + std::to_string(k),
                       reference,
                       cv::imread(img.string(), cv::IMREAD_GRAYSCALE),
                       readHomography(hf)};
      if (p.frame.empty()) throw Error("pairs: cannot read " + img.string());
      out.push_back(std::move(p));
    }
    for (const ViewSpec& v : kViews) {
      const cv::Matx33d H =
          syntheticViewHomography(reference.size(), v.tiltDeg, v.azimuthDeg, v.scale, v.rollDeg);
      char label[96];
      std::snprintf(label, sizeof label, "tilt %.0f az %.0f scale %.1f roll %.0f", v.tiltDeg,
                    v.azimuthDeg, v.scale, v.rollDeg);
      out.push_back({name + "-views", v.kind, label, reference,
                     synthesiseView(reference, H, noiseSigma, mixSeed(seed, ++n)), H});
    }
  }
  return out;
}

void PairsOptions::check() const {
  if (!(noiseSigma >= 0.0 && noiseSigma <= 100.0))
    throw Error("pairs: noiseSigma must be in [0, 100]");
  if (wallSupersample < 1 || wallSupersample > 8)
    throw Error("pairs: wallSupersample must be in [1, 8]");
  params.check();
}

PairsResult runPairsExperiment(const PairsOptions& options) {
  options.check();
  PairsResult out;
  out.pairs = buildHomographyPairs(options.dataDir, options.noiseSigma, options.seed);
  if (!options.broadViews)
    std::erase_if(out.pairs, [](const HomographyPair& p) { return p.kind != "photometric"; });
  if (options.hardSets)
    for (HomographyPair& p : buildHardHomographyPairs(options.dataDir, options.noiseSigma,
                                                      options.seed, options.wallSupersample))
      out.pairs.push_back(std::move(p));
  if (!options.onlySets.empty())
    std::erase_if(out.pairs, [&](const HomographyPair& p) {
      return std::find(options.onlySets.begin(), options.onlySets.end(), p.sequence) ==
             options.onlySets.end();
    });
  if (out.pairs.empty()) throw Error("pairs: no pair of the sets asked for");
  TrackerParams nccOnly = options.params;
  nccOnly.homography.keypoints = KeypointLayer::None;
  const std::vector<std::string> names = {"reftrack", "reftrack-ncc", "sift", "akaze", "orb"};
  for (const std::string& name : names) out.methods.push_back({name, {}});
  ProgressBar progress("pairs", out.pairs.size() * names.size(), "pair");
  // One tracker / baseline per reference image (the reference's features are computed once).
  size_t begin = 0;
  while (begin < out.pairs.size()) {
    size_t end = begin;
    while (end < out.pairs.size() && out.pairs[end].sequence == out.pairs[begin].sequence) ++end;
    const cv::Mat& reference = out.pairs[begin].reference;
    for (size_t m = 0; m < names.size(); ++m) {
      const bool tracker = m < 2;
      std::optional<HomographyTracker> t;
      std::optional<OpenCvFeatureBaseline> b;
      if (tracker)
        t.emplace(reference, m == 0 ? options.params : nccOnly);
      else
        b.emplace(names[m], reference);
      for (size_t i = begin; i < end; ++i) {
        const HomographyPair& p = out.pairs[i];
        PairOutcome o;
        cv::Matx33d H;
        o.milliseconds = timedMs([&] {
          if (tracker) {
            t->reset();
            const HomographyTrackResult r = t->track(p.frame);
            o.found = r.tracked;
            o.failure = r.failure;
            H = r.H;
          } else {
            const FeatureBaselineResult r = b->registerFrame(p.frame);
            o.found = r.found;
            H = r.H;
          }
        });
        o.cornerErrorPx = o.found ? frameCornerError(H, p.truth, p.frame.size())
                                  : std::numeric_limits<double>::quiet_NaN();
        out.methods[m].outcomes.push_back(o);
        progress.advance();
      }
    }
    begin = end;
  }
  progress.finish();
  return out;
}

}  // namespace reftrack::app
