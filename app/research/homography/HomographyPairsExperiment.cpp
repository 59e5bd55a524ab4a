#include "app/research/homography/HomographyPairsExperiment.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
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

// H1toNp.xml (OpenCV storage) or H1toNp (nine numbers, the benchmark's original text format).
cv::Matx33d readHomography(const std::filesystem::path& file) {
  cv::Mat H;
  if (file.extension() == ".xml") {
    cv::FileStorage fs(file.string(), cv::FileStorage::READ);
    if (fs.isOpened()) fs.getFirstTopLevelNode() >> H;
  } else {
    std::ifstream in(file);
    std::vector<double> v;
    for (double x; v.size() < 10 && in >> x;) v.push_back(x);
    if (v.size() == 9) H = cv::Mat(3, 3, CV_64F, v.data()).clone();
  }
  if (H.rows != 3 || H.cols != 3)
    throw Error("pairs: cannot read a 3x3 homography from " + file.string());
  H.convertTo(H, CV_64F);
  cv::Matx33d out(H);
  // Scaled to h33 = 1: the sets' files hold H up to scale (leuven's H1to5p has h33 = -0.58).
  if (std::abs(out(2, 2)) > 1e-12) out *= 1.0 / out(2, 2);
  if (!std::isfinite(cv::norm(out)) || std::abs(cv::determinant(out)) < 1e-12)
    throw Error("pairs: the homography in " + file.string() + " is not finite and invertible");
  return out;
}

constexpr const char* kImageExtensions[] = {".png",  ".ppm", ".pgm", ".jpg",
                                            ".jpeg", ".bmp", ".tif", ".tiff"};

// dir/<stem><ext> for the first image extension that exists; empty when none does.
std::filesystem::path findImage(const std::filesystem::path& dir, const std::string& stem) {
  for (const char* ext : kImageExtensions)
    if (std::filesystem::is_regular_file(dir / (stem + ext))) return dir / (stem + ext);
  return {};
}

std::filesystem::path findHomographyFile(const std::filesystem::path& dir, int k) {
  const std::string stem = "H1to" + std::to_string(k) + "p";
  for (const std::string& name : {stem + ".xml", stem})
    if (std::filesystem::is_regular_file(dir / name)) return dir / name;
  return {};
}

cv::Mat readGrey(const std::filesystem::path& file) {
  const cv::Mat image = cv::imread(file.string(), cv::IMREAD_GRAYSCALE);
  if (image.empty()) throw Error("pairs: cannot read the image " + file.string());
  return image;
}

// Thread CPU time of f (what one core spends on it, whatever else the machine runs).
template <class F>
double timedMs(F&& f) {
  const double t0 = threadCpuMs();
  f();
  return threadCpuMs() - t0;
}

}  // namespace

std::vector<std::filesystem::path> findPairSequences(const std::filesystem::path& dataDir) {
  if (!std::filesystem::is_directory(dataDir))
    throw Error("pairs: " + dataDir.string() + " is not a folder");
  if (!findImage(dataDir, "img1").empty()) return {dataDir};
  std::vector<std::filesystem::path> out;
  for (auto it = std::filesystem::recursive_directory_iterator(
           dataDir, std::filesystem::directory_options::skip_permission_denied);
       it != std::filesystem::recursive_directory_iterator(); ++it) {
    if (!it->is_directory()) continue;
    if (!findImage(it->path(), "img1").empty()) {
      out.push_back(it->path());
      it.disable_recursion_pending();
    } else if (it.depth() >= 2) {
      it.disable_recursion_pending();
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<HomographyPair> buildHomographyPairs(const std::filesystem::path& dataDir,
                                                 double noiseSigma, std::uint64_t seed,
                                                 bool syntheticViews) {
  const std::vector<std::filesystem::path> sequences = findPairSequences(dataDir);
  if (sequences.empty())
    throw Error("pairs: no sequence folder with img1 (.png, .ppm, .pgm, .jpg) under " +
                dataDir.string());
  std::vector<HomographyPair> out;
  std::uint64_t n = 0;
  for (const auto& dir : sequences) {
    const std::string name = dir.filename().string();
    const std::string kind = dir.parent_path().filename().string();
    const cv::Mat reference = readGrey(findImage(dir, "img1"));
    for (int k = 2; k <= 9; ++k) {
      const auto img = findImage(dir, "img" + std::to_string(k));
      const auto hf = findHomographyFile(dir, k);
      if (img.empty() || hf.empty()) continue;
      HomographyPair p{name,      kind,          "1->" + std::to_string(k),
                       reference, readGrey(img), readHomography(hf),
                       true};
      out.push_back(std::move(p));
    }
    if (!syntheticViews) continue;
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

// The pair with both images resampled by s and H carried over: H_s = S H S^-1, S = diag(s, s, 1)
// about pixel centres (x_s = s (x + 0.5) - 0.5).
HomographyPair resampledPair(const HomographyPair& p, double s) {
  HomographyPair out = p;
  const auto resize = [s](const cv::Mat& image) {
    cv::Mat r;
    const cv::Size size(std::max(1, static_cast<int>(std::lround(image.cols * s))),
                        std::max(1, static_cast<int>(std::lround(image.rows * s))));
    cv::resize(image, r, size, 0, 0, s < 1.0 ? cv::INTER_AREA : cv::INTER_CUBIC);
    return r;
  };
  out.reference = resize(p.reference);
  out.frame = resize(p.frame);
  const auto scaling = [](double sx, double sy) {
    return cv::Matx33d(sx, 0, 0.5 * sx - 0.5, 0, sy, 0.5 * sy - 0.5, 0, 0, 1);
  };
  const cv::Matx33d Sr = scaling(static_cast<double>(out.reference.cols) / p.reference.cols,
                                 static_cast<double>(out.reference.rows) / p.reference.rows);
  const cv::Matx33d Sf = scaling(static_cast<double>(out.frame.cols) / p.frame.cols,
                                 static_cast<double>(out.frame.rows) / p.frame.rows);
  out.truth = Sf * p.truth * Sr.inv();
  out.truth *= 1.0 / out.truth(2, 2);
  char name[32];
  std::snprintf(name, sizeof name, "@%g", s);
  out.sequence += name;
  return out;
}

void PairsOptions::check() const {
  if (!(noiseSigma >= 0.0 && noiseSigma <= 100.0))
    throw Error("pairs: noiseSigma must be in [0, 100]");
  for (double s : scales)
    if (!(s >= 0.1 && s <= 4.0)) throw Error("pairs: every scale must be in [0.1, 4]");
  if (scales.empty()) throw Error("pairs: scales must not be empty");
  if (wallSupersample < 1 || wallSupersample > 8)
    throw Error("pairs: wallSupersample must be in [1, 8]");
  params.check();
}

PairsResult runPairsExperiment(const PairsOptions& options) {
  options.check();
  PairsResult out;
  out.pairs =
      buildHomographyPairs(options.dataDir, options.noiseSigma, options.seed, options.broadViews);
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
  if (options.refineTruth) {
    ProgressBar checking("truth check (ECC)", out.pairs.size(), "pair");
    for (HomographyPair& p : out.pairs) {
      RefinedTruth t;
      if (p.real) {
        t = refineTruthByEcc(p.reference, p.frame, p.truth);
        if (t.converged) p.truth = t.H;
      }
      out.truthChecks.push_back(t);
      checking.advance();
    }
    checking.finish();
  }
  if (options.scales != std::vector<double>{1.0}) {
    std::vector<HomographyPair> scaled;
    std::vector<RefinedTruth> checks;
    for (double s : options.scales)
      for (size_t i = 0; i < out.pairs.size(); ++i) {
        if (!out.pairs[i].real && s != 1.0) continue;
        scaled.push_back(s == 1.0 ? out.pairs[i] : resampledPair(out.pairs[i], s));
        if (!out.truthChecks.empty()) checks.push_back(out.truthChecks[i]);
      }
    out.pairs = std::move(scaled);
    out.truthChecks = std::move(checks);
  }
  TrackerParams nccOnly = options.params;
  nccOnly.homography.keypoints = KeypointLayer::None;
  std::vector<std::string> names = {"reftrack", "reftrack-ncc"};
  if (options.peers) names.insert(names.end(), {"sift", "akaze", "orb"});
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
        const auto wall0 = std::chrono::steady_clock::now();
        o.milliseconds = timedMs([&] {
          if (tracker) {
            t->reset();
            const HomographyTrackResult r = t->track(p.frame);
            o.found = r.tracked;
            o.failure = r.failure;
            o.check = r.check;
            o.stageMs = r.stageMs;
            H = r.H;
          } else {
            const FeatureBaselineResult r = b->registerFrame(p.frame);
            o.found = r.found;
            H = r.H;
          }
        });
        o.wallMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall0)
                .count();
        constexpr double nan = std::numeric_limits<double>::quiet_NaN();
        o.cornerErrorPx = o.found ? referenceCornerError(H, p.truth, p.reference.size()) : nan;
        o.overlapErrorPx =
            o.found ? meanTransferDeviation(H, p.truth, annotationGrid(p.reference.size(), 32, 24),
                                            p.frame.size())
                    : nan;
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
