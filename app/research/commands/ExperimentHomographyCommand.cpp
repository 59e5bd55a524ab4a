// `reftrack experiment-homography`: the paper's homography-mode experiments (Sec. 7.3) on the
// simulator with exact ground truth — a static camera over many noisy frames (centre deviation)
// and a pure-rotation sweep with a 33 degree field of view (success rate and annotation error
// per angle, paper Fig. 15/16) — plus cold registration of a planar target from any view
// (simulator) and real image pairs with known homographies against plain OpenCV baselines.
// Prints a table per experiment and writes PNG plots.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <opencv2/core/utility.hpp>
#include <string>
#include <vector>

#include "app/cli/CameraEffectsValidator.hpp"
#include "app/cli/DistortionOption.hpp"
#include "app/cli/ImageSizeValidator.hpp"
#include "app/commands/Commands.hpp"
#include "app/plot/PlotCanvas.hpp"
#include "app/research/homography/ColdRegistrationExperiment.hpp"
#include "app/research/homography/HardHomographyPairs.hpp"
#include "app/research/homography/HomographyPairsExperiment.hpp"
#include "app/research/homography/RotationSweepExperiment.hpp"
#include "app/research/homography/StaticHomographyExperiment.hpp"
#include "app/research/homography/VerifierCalibration.hpp"
#include "app/simulator/SimulationOptions.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {

namespace {

struct ExperimentArgs {
  std::string experiment = "all";
  std::string size = "320x240";
  int frames = 500;
  int trials = 100;
  double maxAngle = 33.0;
  double step = 3.0;
  double noise = 2.0;
  std::uint64_t seed = 1;
  bool uncalibrated = false;
  std::vector<double> distortion;
  std::filesystem::path params;
  std::filesystem::path out = "experiment-homography";
  int coldTrials = 200;
  double maxTilt = 50.0;
  double minScale = 0.5, maxScale = 2.0;
  std::filesystem::path data = "../shared/data";
  double pairsErrorPx = 3.0;
  double pairsWrongPx = 10.0;
  bool synthetic = false;
  bool noPeers = false;
  std::string pairsMetric = "overlap";
  std::string pairsTruth = "given";
  std::vector<double> pairsScales = {1.0};
  std::filesystem::path savePairs;
  std::vector<std::string> onlySets;
  std::string effects = "none";
};

void printColdTable(const std::vector<ColdBucket>& buckets) {
  std::printf("%-18s %-9s %-9s %-7s %-15s %-15s %-9s\n", "bucket", "trials", "success", "wrong",
              "mean err (px)", "max err (px)", "ms_med");
  for (const ColdBucket& b : buckets)
    std::printf("%-18s %-9d %5.1f%%    %-7d %-15.4f %-15.4f %-9.2f\n", b.label.c_str(), b.trials,
                100.0 * b.successes / std::max(1, b.trials), b.wrong, b.meanErrorPx, b.maxErrorPx,
                b.medianMs);
}

void runCold(const ExperimentArgs& a, cv::Size size, const TrackerParams& params) {
  ColdRegistrationOptions o;
  o.size = size;
  o.trials = a.coldTrials;
  o.maxTiltDeg = a.maxTilt;
  o.minScale = a.minScale;
  o.maxScale = a.maxScale;
  o.noiseSigma = a.noise;
  o.seed = a.seed;
  o.params = params;
  const std::vector<ColdTrial> trials = runColdRegistration(o);
  int keypoint = 0;
  for (const ColdTrial& t : trials) keypoint += t.keypointGuided ? 1 : 0;
  std::printf(
      "cold registration of a planar target, %dx%d, 60 deg field of view, %d first frames, "
      "keypoints: %s (%d registered through them)\n",
      size.width, size.height, o.trials, keypointLayerName(params.homography.keypoints).c_str(),
      keypoint);
  std::vector<double> tiltEdges;
  for (double t = 0; t < o.maxTiltDeg - 1e-9; t += 10) tiltEdges.push_back(t);
  tiltEdges.push_back(o.maxTiltDeg);
  printColdTable(bucketByTilt(trials, tiltEdges, o.successErrorPx));
  std::printf("\n");
  printColdTable(bucketByScale(
      trials, {o.minScale, std::max(o.minScale, 0.71), std::min(o.maxScale, 1.41), o.maxScale},
      o.successErrorPx));
  std::printf("\nnot registered or wrong (tilt, scale, in-plane rotation: why):\n");
  for (const ColdTrial& t : trials)
    if (!t.tracked || !(t.cornerErrorPx <= o.successErrorPx))
      std::printf("  %5.1f deg %4.2fx %5.1f deg: %s\n", t.tiltDeg, t.scale, t.rollDeg,
                  t.tracked ? ("error " + std::to_string(t.cornerErrorPx) + " px").c_str()
                            : t.failure.c_str());
  std::printf("\n");
}

// The chosen error of one outcome (NaN when nothing was returned).
double pairError(const PairOutcome& o, const std::string& metric) {
  return metric == "overlap" ? o.overlapErrorPx : o.cornerErrorPx;
}

std::string sizeName(cv::Size s) {
  return std::to_string(s.width) + "x" + std::to_string(s.height);
}

void runPairs(const ExperimentArgs& a, const TrackerParams& params) {
  PairsOptions o;
  o.dataDir = a.data;
  o.noiseSigma = a.noise;
  o.seed = a.seed;
  o.broadViews = a.synthetic;
  o.hardSets = a.synthetic;
  o.onlySets = a.onlySets;
  o.peers = !a.noPeers;
  o.refineTruth = a.pairsTruth == "refined";
  o.scales = a.pairsScales;
  o.params = params;
  if (!a.savePairs.empty()) {
    saveHomographyPairs(buildHardHomographyPairs(a.data, a.noise, a.seed), a.savePairs);
    std::printf("hard sets written under %s\n", a.savePairs.string().c_str());
  }
  const PairsResult r = runPairsExperiment(o);
  const std::string& metric = a.pairsMetric;
  if (o.refineTruth) {
    // How far ECC moves each given homography: the truth's own error, where it converges.
    std::printf(
        "truth check: the given homography refined by OpenCV's ECC (findTransformECC, 5x5 "
        "Gaussian): distance moved at the reference's corners (px) and ECC correlation\n");
    for (size_t i = 0; i < r.pairs.size(); ++i) {
      if (!r.pairs[i].real || r.pairs[i].sequence.find('@') != std::string::npos) continue;
      const RefinedTruth& t = r.truthChecks[i];
      if (t.converged)
        std::printf("  %-10s %-6s moved %6.2f px  correlation %.3f%s\n",
                    r.pairs[i].sequence.c_str(), r.pairs[i].label.c_str(), t.movedPx, t.correlation,
                    t.movedPx > 1.0 ? "  <- the given H is off" : "");
      else
        std::printf("  %-10s %-6s ECC did not converge: the given H kept\n",
                    r.pairs[i].sequence.c_str(), r.pairs[i].label.c_str());
    }
    std::printf("\n");
  }
  std::printf(
      "image pairs with known homographies under %s; error: %s; registered: error <= %.1f px; "
      "wrong: a homography returned with an error > %.1f px; off: returned, in between; ms: wall "
      "clock per cold registration, median, one thread (cpu: thread CPU); reftrack keypoints: "
      "%s\n",
      (a.data.string() + (o.refineTruth ? " (truth: the given H refined by ECC)" : "")).c_str(),
      metric == "overlap" ? "mean over the reference points the frame sees (overlap)"
                          : "mean at the reference image's four corners (Oxford convention)",
      a.pairsErrorPx, a.pairsWrongPx, keypointLayerName(params.homography.keypoints).c_str());
  // One table row per (group, method): a group is a pair set, a frame size or a union of sets.
  const auto table = [&](const char* heading, const std::vector<std::string>& groups,
                         const std::function<bool(const HomographyPair&, const std::string&)>& in) {
    std::printf("%-22s %-13s %-12s %-7s %-5s %-6s %-13s %-11s %-8s %-8s\n", heading, "method",
                "registered", "wrong", "off", "lost", "mean err(px)", "median err", "ms_med",
                "cpu_med");
    for (const std::string& group : groups) {
      for (const PairsMethod& m : r.methods) {
        int n = 0, ok = 0, wrong = 0, off = 0, lost = 0;
        std::vector<double> errors, ms, cpu;
        for (size_t i = 0; i < r.pairs.size(); ++i) {
          if (!in(r.pairs[i], group)) continue;
          ++n;
          const PairOutcome& o2 = m.outcomes[i];
          ms.push_back(o2.wallMs);
          cpu.push_back(o2.milliseconds);
          const double e = pairError(o2, metric);
          if (!o2.found) {
            ++lost;
          } else if (e <= a.pairsErrorPx) {
            ++ok;
            errors.push_back(e);
          } else if (!(e <= a.pairsWrongPx)) {
            ++wrong;
          } else {
            ++off;
          }
        }
        if (n == 0) continue;
        double mean = errors.empty() ? NAN : 0.0;
        for (double e : errors) mean += e / static_cast<double>(errors.size());
        std::sort(errors.begin(), errors.end());
        std::sort(ms.begin(), ms.end());
        std::sort(cpu.begin(), cpu.end());
        std::printf("%-22s %-13s %4d/%-7d %-7d %-5d %-6d %-13.3f %-11.3f %-8.1f %-8.1f\n",
                    group.c_str(), m.name.c_str(), ok, n, wrong, off, lost, mean,
                    errors.empty() ? NAN : errors[errors.size() / 2], ms[ms.size() / 2],
                    cpu[cpu.size() / 2]);
      }
    }
    std::printf("\n");
  };
  std::vector<std::string> sequences, sizes;
  const auto addOnce = [](std::vector<std::string>& v, const std::string& x) {
    if (std::find(v.begin(), v.end(), x) == v.end()) v.push_back(x);
  };
  for (const HomographyPair& p : r.pairs) {
    addOnce(sequences, p.sequence);
    if (p.real) addOnce(sizes, sizeName(p.frame.size()));
  }
  table("pair set", sequences,
        [](const HomographyPair& p, const std::string& g) { return p.sequence == g; });
  table("frame size (real)", sizes, [](const HomographyPair& p, const std::string& g) {
    return p.real && sizeName(p.frame.size()) == g;
  });
  std::vector<std::string> unions = {"all real pairs"};
  if (a.synthetic) unions.insert(unions.end(), {"synthesised views", "simulated hard sets"});
  const std::vector<std::string>& hard = hardPairSetNames();
  table("union of sets", unions, [&](const HomographyPair& p, const std::string& g) {
    const bool isHard = std::find(hard.begin(), hard.end(), p.sequence) != hard.end();
    if (g == "all real pairs") return p.real;
    if (g == "simulated hard sets") return isHard;
    return !p.real && !isHard;
  });
  // Where reftrack's time goes: per stage, the median over the real pairs of each frame size.
  std::printf(
      "reftrack's stages, ms per cold registration (median over the pairs of a frame size, "
      "wall clock)\n%-12s",
      "frame size");
  const std::vector<std::pair<std::string, double>>& stagesOf0 = r.methods[0].outcomes[0].stageMs;
  for (const auto& [name, ms] : stagesOf0) std::printf(" %-10s", name.c_str());
  std::printf("\n");
  for (const std::string& size : sizes) {
    std::printf("%-12s", size.c_str());
    for (size_t k = 0; k < stagesOf0.size(); ++k) {
      std::vector<double> v;
      for (size_t i = 0; i < r.pairs.size(); ++i) {
        const PairOutcome& own = r.methods[0].outcomes[i];
        if (r.pairs[i].real && sizeName(r.pairs[i].frame.size()) == size && k < own.stageMs.size())
          v.push_back(own.stageMs[k].second);
      }
      std::sort(v.begin(), v.end());
      std::printf(" %-10.1f", v.empty() ? NAN : v[v.size() / 2]);
    }
    std::printf("\n");
  }
  std::printf("\n");
  // reftrack's cost beside SIFT's on the same pairs (thread CPU, measured in this run): the
  // median per frame size and the median of the per-pair ratios.
  const auto methodIndex = [&](const std::string& name) {
    for (size_t m = 0; m < r.methods.size(); ++m)
      if (r.methods[m].name == name) return static_cast<int>(m);
    return -1;
  };
  if (const int sift = methodIndex("sift"); sift >= 0) {
    std::printf(
        "cold registration cost beside SIFT's (thread CPU per pair, one thread, this run): "
        "median ms, and the median of reftrack / SIFT per pair\n%-22s %-8s %-12s %-12s %-10s\n",
        "frame size", "pairs", "reftrack ms", "sift ms", "ratio");
    std::vector<std::string> groups = sizes;
    groups.push_back("all real pairs");
    for (const std::string& size : groups) {
      std::vector<double> own, peer, ratio;
      for (size_t i = 0; i < r.pairs.size(); ++i) {
        if (!r.pairs[i].real ||
            (size != "all real pairs" && sizeName(r.pairs[i].frame.size()) != size))
          continue;
        own.push_back(r.methods[0].outcomes[i].milliseconds);
        peer.push_back(r.methods[static_cast<size_t>(sift)].outcomes[i].milliseconds);
        ratio.push_back(own.back() / std::max(1e-6, peer.back()));
      }
      if (own.empty()) continue;
      const auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        const size_t n = v.size();
        return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
      };
      std::printf("%-22s %-8zu %-12.1f %-12.1f %-10.3f\n", size.c_str(), own.size(), median(own),
                  median(peer), median(ratio));
    }
    std::printf("\n");
  }
  // What reftrack's registration check compared on each pair (the inliers' region or the whole
  // overlap) and found.
  std::printf("reftrack's registration check per pair:\n");
  for (size_t i = 0; i < r.pairs.size(); ++i) {
    const PairOutcome& own = r.methods.front().outcomes[i];
    if (own.check.empty()) continue;
    std::printf("  %-14s %-10s %s: %s\n", r.pairs[i].sequence.c_str(), r.pairs[i].label.c_str(),
                own.found ? "passed" : "refused", own.check.c_str());
  }
  std::printf("\n");
  // The pairs the first method (reftrack) does not register within the bound, with every
  // method's error (- = no homography returned) and reftrack's reason.
  std::printf("pairs reftrack misses (%s error per method, - = none returned):\n", metric.c_str());
  for (size_t i = 0; i < r.pairs.size(); ++i) {
    const PairOutcome& own = r.methods.front().outcomes[i];
    if (own.found && pairError(own, metric) <= a.pairsErrorPx) continue;
    std::printf("  %-14s %-34s", r.pairs[i].sequence.c_str(), r.pairs[i].label.c_str());
    for (const PairsMethod& m : r.methods) {
      const PairOutcome& o2 = m.outcomes[i];
      if (o2.found)
        std::printf(" %s %.2f", m.name.c_str(), pairError(o2, metric));
      else
        std::printf(" %s -", m.name.c_str());
    }
    if (!own.found) std::printf("\n      reftrack: %s", own.failure.c_str());
    std::printf("\n");
  }
  std::printf("\n");
}

void runVerify(const ExperimentArgs& a, const TrackerParams& params) {
  std::vector<HomographyPair> pairs = buildHomographyPairs(a.data, a.noise, a.seed, a.synthetic);
  if (a.synthetic)
    for (HomographyPair& p : buildHardHomographyPairs(a.data, a.noise, a.seed))
      pairs.push_back(std::move(p));
  if (!a.onlySets.empty())
    std::erase_if(pairs, [&](const HomographyPair& p) {
      return std::find(a.onlySets.begin(), a.onlySets.end(), p.sequence) == a.onlySets.end();
    });
  const std::vector<double> offsets = {1, 2, 3, 5, 10, 20};
  constexpr int kTrials = 4;
  const RegistrationCheckParams check = RegistrationCheckParams::from(params.homography);
  const std::vector<VerifierPairResult> r =
      runVerifierCalibration(pairs, offsets, kTrials, a.seed, check);
  std::printf(
      "registration check on pairs with known homographies: the truth, and the truth with each "
      "frame corner moved by d px in a random direction (%d trials per pair and d); passed / "
      "checked, and the median offset the check measured (px; score >= %.2f, search "
      "+-%.1f px, tolerance %.2f px at 320x240, fraction >= %.2f, spread >= %.2f, offset <= "
      "%.2f px at 320x240)\n",
      kTrials, check.minScore, check.searchRadiusAt320, check.confirmToleranceAt320,
      check.minConfirmedFraction, check.minSpread, check.maxOffsetAt320);
  std::printf("%-16s %-14s", "pair set", "truth");
  for (double d : offsets) std::printf(" d=%-11.0f", d);
  std::printf("\n");
  std::vector<std::string> sets;
  for (const HomographyPair& p : pairs)
    if (std::find(sets.begin(), sets.end(), p.sequence) == sets.end()) sets.push_back(p.sequence);
  sets.push_back("all");
  for (const std::string& set : sets) {
    std::printf("%-16s", set.c_str());
    for (int k = -1; k < static_cast<int>(offsets.size()); ++k) {
      const double d = k < 0 ? 0.0 : offsets[static_cast<size_t>(k)];
      int n = 0, passed = 0;
      std::vector<double> measured;
      for (size_t i = 0; i < pairs.size(); ++i) {
        if (set != "all" && pairs[i].sequence != set) continue;
        for (const VerifierOutcome& o : r[i].outcomes)
          if (o.offsetPx == d) {
            ++n;
            passed += o.passed ? 1 : 0;
            measured.push_back(o.measuredOffsetPx);
          }
      }
      std::sort(measured.begin(), measured.end());
      char cell[40];
      std::snprintf(cell, sizeof cell, "%d/%d %.1f", passed, n,
                    measured.empty() ? NAN : measured[measured.size() / 2]);
      std::printf(" %-13s", cell);
    }
    std::printf("\n");
  }
  std::printf("true homographies refused, and homographies >= 10 px off passed:\n");
  for (size_t i = 0; i < pairs.size(); ++i)
    for (const VerifierOutcome& o : r[i].outcomes)
      if ((o.offsetPx == 0.0 && !o.passed) || (o.offsetPx >= 10.0 && o.passed))
        std::printf("  %-14s %-34s d=%-4.0f measured %.1f px, %d of %d confirm: %s\n",
                    pairs[i].sequence.c_str(), pairs[i].label.c_str(), o.offsetPx,
                    o.measuredOffsetPx, o.confirmed, o.measurable,
                    o.passed ? "passed" : o.failure.c_str());
  std::printf("\n");
}

void runStatic(const ExperimentArgs& a, cv::Size size, const TrackerParams& params) {
  StaticExperimentOptions o;
  o.size = size;
  o.frames = a.frames;
  o.noiseSigma = a.noise;
  o.seed = a.seed;
  o.params = params;
  o.effects = cameraEffectsFor(a.effects, size);
  const StaticExperimentResult r = runStaticExperiment(o);
  std::vector<double> index, deviation;
  for (int k = 0; k < r.frames; ++k) {
    index.push_back(k);
    deviation.push_back(r.centreDeviationPx[static_cast<size_t>(k)]);
  }
  std::vector<double> ms = r.milliseconds;
  std::sort(ms.begin(), ms.end());
  std::printf("static camera, %dx%d, 33 deg field of view, noise %.1f, effects %s\n", size.width,
              size.height, a.noise, a.effects.c_str());
  std::printf("%-12s %-22s %-22s %-12s\n", "registered", "mean centre dev (px)",
              "max centre dev (px)", "ms_median");
  std::printf("%5d/%-6d %-22.4f %-22.4f %-12.3f\n\n", r.registered, r.frames, r.meanDeviationPx,
              r.maxDeviationPx, ms.empty() ? NAN : ms[ms.size() / 2]);
  PlotCanvas plot("Static camera: deviation of the mapped image centre", "frame", "deviation (px)");
  plot.addLine("centre deviation", index, deviation, cv::Scalar(200, 80, 20));
  plot.save(a.out / "static_centre_deviation.png");
}

void runRotation(const ExperimentArgs& a, cv::Size size, const TrackerParams& params) {
  RotationSweepOptions o;
  o.size = size;
  o.maxAngleDeg = a.maxAngle;
  o.stepDeg = a.step;
  o.trials = a.trials;
  o.noiseSigma = a.noise;
  o.seed = a.seed;
  o.params = params;
  o.calibrated = !a.uncalibrated;
  o.effects = cameraEffectsFor(a.effects, size);
  o.distortion = a.distortion;
  const std::vector<RotationStep> steps = runRotationSweep(o);
  std::printf("pure rotation sweep, %dx%d, 33 deg field of view, %d trials per angle, %s\n",
              size.width, size.height, a.trials,
              o.calibrated ? "calibrated (K given: the rotation-only model where the general "
                             "homography fails or rests on a thin strip)"
                           : "uncalibrated (general homography only)");
  for (std::size_t i = 0; i < o.distortion.size(); ++i)
    std::printf("%s%g", i ? "," : "lens distortion ", o.distortion[i]);
  if (!o.distortion.empty()) std::printf(" (frames undistorted before registration)\n");
  std::printf("%-9s %-9s %-9s %-9s %-9s %-15s %-15s %-15s %-9s\n", "angle", "overlap", "success",
              "rot.model", "wrong", "mean err (px)", "median err", "max err", "ms_med");
  std::vector<double> angle, success, meanError, medianError;
  for (const RotationStep& s : steps) {
    const double rate = 100.0 * s.successes / std::max(1, s.trials);
    std::printf("%-9.1f %-9.2f %5.0f%%    %-9d %-9d %-15.4f %-15.4f %-15.4f %-9.3f\n", s.angleDeg,
                s.overlap, rate, s.rotationModelSuccesses, s.trackedButWrong, s.meanErrorPx,
                s.medianErrorPx, s.maxErrorPx, s.medianMs);
    angle.push_back(s.angleDeg);
    success.push_back(rate);
    meanError.push_back(s.meanErrorPx);
    medianError.push_back(s.medianErrorPx);
  }
  std::printf("\n");
  PlotCanvas errorPlot("Annotation error vs rotation (paper Fig. 15)", "rotation (deg)",
                       "annotation error (px)");
  errorPlot.addLine("mean", angle, meanError, cv::Scalar(200, 80, 20));
  errorPlot.addLine("median", angle, medianError, cv::Scalar(40, 160, 40));
  errorPlot.save(a.out / "rotation_annotation_error.png");
  PlotCanvas successPlot("Successful trials vs rotation (paper Fig. 16)", "rotation (deg)",
                         "success (%)");
  successPlot.addLine("success", angle, success, cv::Scalar(30, 30, 200));
  successPlot.save(a.out / "rotation_success.png");
}

CommandRegistration registerExperimentHomographyCommand(CLI::App& parent) {
  auto args = std::make_shared<ExperimentArgs>();
  CLI::App* sub = parent.add_subcommand(
      "experiment-homography",
      "Homography-mode experiments: static camera and pure-rotation sweep (paper Fig. 15/16)");
  sub->add_option("--experiment", args->experiment, "Which experiment")
      ->check(CLI::IsMember({"static", "rotation", "all", "cold", "pairs", "verify"}))
      ->capture_default_str();
  sub->add_option("--size", args->size, "Image size WIDTHxHEIGHT")
      ->check(imageSizeValidator())
      ->capture_default_str();
  sub->add_option("--frames", args->frames, "Static: frames")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--trials", args->trials, "Rotation: trials per angle")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--max-angle", args->maxAngle, "Rotation: largest angle (degrees)")
      ->check(CLI::Range(0.0, 90.0))
      ->capture_default_str();
  sub->add_option("--step", args->step, "Rotation: angle step (degrees)")
      ->check(CLI::Range(0.1, 90.0))
      ->capture_default_str();
  sub->add_option("--noise", args->noise, "Sensor noise SD (grey levels)")
      ->check(CLI::Range(0.0, 50.0))
      ->capture_default_str();
  sub->add_option("--seed", args->seed, "Sensor noise seed")->capture_default_str();
  sub->add_flag("--uncalibrated", args->uncalibrated,
                "Rotation: do not give the tracker K (no rotation-only model)");
  addDistortionOption(sub, args->distortion)
      ->description(
          "Rotation: lens distortion k1,k2,p1,p2[,k3] of the simulated camera (frames are "
          "undistorted before registration; errors in undistorted pixels); default none");
  sub->add_option("--cold-trials", args->coldTrials, "Cold: first frames (random views)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--max-tilt", args->maxTilt, "Cold: largest out-of-plane rotation (degrees)")
      ->check(CLI::Range(0.0, 70.0))
      ->capture_default_str();
  sub->add_option("--min-scale", args->minScale, "Cold: smallest scale")
      ->check(CLI::Range(0.25, 4.0))
      ->capture_default_str();
  sub->add_option("--max-scale", args->maxScale, "Cold: largest scale")
      ->check(CLI::Range(0.25, 4.0))
      ->capture_default_str();
  sub->add_option("--data", args->data,
                  "Pairs: a folder of real pairs (img1 + imgN + H1toNp[.xml]) or of such folders")
      ->capture_default_str();
  sub->add_option("--pairs-error", args->pairsErrorPx, "Pairs: registered up to this error (px)")
      ->check(CLI::Range(0.1, 100.0))
      ->capture_default_str();
  sub->add_option("--pairs-wrong", args->pairsWrongPx,
                  "Pairs: a registration returned with a larger error is wrong (px)")
      ->check(CLI::Range(0.1, 1000.0))
      ->capture_default_str();
  sub->add_option("--save-pairs", args->savePairs,
                  "Pairs: also write the hard sets as Oxford-style folders here (img1.png = the "
                  "reference, img2..6.png, H1toNp.xml)");
  sub->add_option("--sets", args->onlySets,
                  "Pairs: register only these pair sets (names as in the table, e.g. wall-sim "
                  "bikes)");
  sub->add_flag("--synthetic", args->synthetic,
                "Pairs and verify: add views synthesised from each sequence's img1 and the "
                "simulated hard sets (test material, not evidence)");
  sub->add_flag("--no-peers", args->noPeers, "Pairs: reftrack only (no SIFT, AKAZE, ORB)");
  sub->add_option("--metric", args->pairsMetric,
                  "Pairs: overlap (mean over the reference points the frame sees) or corners "
                  "(mean error at the reference's corners, the Oxford convention: far outside the "
                  "frame on zoomed pairs)")
      ->check(CLI::IsMember({"corners", "overlap"}))
      ->capture_default_str();
  sub->add_option("--truth", args->pairsTruth,
                  "Pairs: given (the data set's homographies) or refined (each refined by "
                  "OpenCV's ECC from the given one where it converges; prints how far it moved)")
      ->check(CLI::IsMember({"given", "refined"}))
      ->capture_default_str();
  sub->add_option("--scales", args->pairsScales,
                  "Pairs: register every real pair with both images resampled by each of these "
                  "factors (e.g. 0.4 1 2: other cameras' sizes; sets named <set>@<scale>)")
      ->check(CLI::Range(0.1, 4.0))
      ->delimiter(',')
      ->capture_default_str();
  sub->add_option("--effects", args->effects,
                  "Static and rotation: webcam effects (none, webcam or a comma-separated list of "
                  "photos, blur, rolling-shutter, exposure, flicker, vignetting, noise, defocus, "
                  "compression); rotation trials get the still ones (photos, defocus, vignetting, "
                  "noise)")
      ->check(cameraEffectsValidator())
      ->capture_default_str();
  sub->add_option("--params", args->params, "TrackerParams YAML")->check(CLI::ExistingFile);
  sub->add_option("--out", args->out, "Folder for the PNG plots")->capture_default_str();
  sub->footer(
      "static: reference view A and --frames frames of the same view, each with fresh sensor\n"
      "noise, tracked as a video; deviation = |H c - c| of the image centre c (paper: 500/500,\n"
      "< 1 px). rotation: per angle, --trials pairs (reference, frame panned alternately left\n"
      "and right about the optical centre) registered cold; error = mean |H_est p - K R K^-1 p|\n"
      "over a 9x7 grid of reference annotations inside the frame; success = tracked with error\n"
      "< 2 px (errors are over the successes); rot.model = successes registered with the\n"
      "rotation-only model K R K^-1 (the tracker is given K unless --uncalibrated); wrong =\n"
      "tracked with a larger error, or placing an annotation that is outside the frame\n"
      "more than 2 px inside it; overlap =\n"
      "fraction of the frame that sees the reference. Writes static_centre_deviation.png,\n"
      "rotation_annotation_error.png and rotation_success.png to --out.\n"
      "cold: a textured 0.4 x 0.3 m card seen head-on is the reference; --cold-trials views of\n"
      "it (tilt uniform in [0, --max-tilt] about a random axis, scale log-uniform in\n"
      "[--min-scale, --max-scale], any in-plane rotation) are each registered as a first frame\n"
      "(reset before each; --size defaults to 640x480 here); success = tracked with a "
      "frame-corner\n"
      "error <= 1 px, wrong = tracked with a larger one; tables by tilt and by scale.\n"
      "pairs: every sequence folder under --data (itself or up to three levels down: img1 and\n"
      "img2..img9 as .png/.ppm/.pgm/.jpg, H1toNp or H1toNp.xml, x_N ~ H1toNp x_1): its real pairs\n"
      "img1 -> imgN (any sizes), registered cold by reftrack, reftrack without keypoints, and\n"
      "OpenCV SIFT, AKAZE and ORB + ratio test + findHomography RANSAC (--no-peers: reftrack "
      "only).\n"
      "Error (--metric): overlap (default) = mean over a 32x24 grid of img1's points that the\n"
      "frame sees; corners = mean at img1's four corners, estimate vs truth. Registered: error <= "
      "--pairs-error;\n"
      "wrong: returned with an error > --pairs-wrong; off: in between. --synthetic adds views\n"
      "synthesised from img1 (tilt 20-60 deg; zoom 0.5-3.5 with rotation) and the simulated hard\n"
      "sets (graf-sim, wall-sim, boat-sim, bark-sim, tiles-sim; they need ubc, bikes and trees\n"
      "directly under --data): test material, not evidence. One thread; tables per set, per frame\n"
      "size and over all real pairs; ms = wall clock, cpu = thread CPU per registration.");
  return {sub, [args, sub] {
            cv::setNumThreads(1);
            const bool coldSize = args->experiment == "cold" && sub->count("--size") == 0;
            const cv::Size size = coldSize ? cv::Size(640, 480) : *parseImageSize(args->size);
            const TrackerParams params =
                args->params.empty() ? TrackerParams{} : TrackerParams::load(args->params);
            params.check();
            // Only the experiments that write plots make the plot folder.
            if (args->experiment != "pairs" && args->experiment != "verify")
              std::filesystem::create_directories(args->out);
            const auto context = render::createHeadlessContext();
            if (args->experiment == "cold") {
              runCold(*args, size, params);
              return;
            }
            if (args->experiment == "pairs") {
              runPairs(*args, params);
              return;
            }
            if (args->experiment == "verify") {
              runVerify(*args, params);
              return;
            }
            if (args->experiment != "rotation") runStatic(*args, size, params);
            if (args->experiment != "static") runRotation(*args, size, params);
            std::printf("plots in %s\n", args->out.string().c_str());
          }};
}

const CommandRegistrar registrar(65, registerExperimentHomographyCommand, CommandGroup::Research);

}  // namespace

}  // namespace reftrack::app
