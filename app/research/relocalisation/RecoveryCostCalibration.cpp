#include "app/research/relocalisation/RecoveryCostCalibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <numeric>
#include <random>

#include "engine/core/Error.hpp"
#include "engine/tracking/MultiReferenceTracker.hpp"

namespace reftrack::app {

namespace {

constexpr int kTerms = 6;

std::array<double, kTerms> terms(const RecoveryWork& w) {
  return {w.startPassMegapixels,           w.seededPassMegapixels,
          w.repeatedPassMegapixels,        w.keypoints.detectedMegapixels,
          w.keypoints.comparisonsMillions, static_cast<double>(w.keypoints.poseSearches)};
}

RecoveryCostModel modelFrom(const std::array<double, kTerms>& c) {
  RecoveryCostModel m;
  m.msPerStartPassMegapixel = c[0];
  m.msPerSeededPassMegapixel = c[1];
  m.msPerRepeatedPassMegapixel = c[2];
  m.msPerDetectedMegapixel = c[3];
  m.msPerMillionComparisons = c[4];
  m.msPerPoseSearch = c[5];
  return m;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

void printAgreement(std::FILE* out, const char* label, const CostModelAgreement& a) {
  std::fprintf(out, "  %-28s %6d %12.0f %12.0f %8.3f %8.3f %8.3f %8.3f\n", label, a.samples,
               a.modelledSumMs, a.measuredSumMs, a.sumRatio, a.medianRatio, a.p10Ratio, a.p90Ratio);
}

}  // namespace

std::vector<RecoverySample> collectRecoverySamples(const MultiReferenceMap& map,
                                                   const std::vector<cv::Mat>& frames,
                                                   TrackerParams params, unsigned seed,
                                                   int repeats) {
  if (repeats < 1) throw Error("recovery cost: repeats must be at least 1");
  // A budget no recovery comes near: every lost frame is searched in full.
  params.relocalisation.budgetBurstMs = 1e9;
  params.relocalisation.budgetMsPerFrame = 1e6;
  const auto play = [&](const std::string& order, const std::vector<int>& indices, bool reset) {
    std::vector<RecoverySample> samples;
    MultiReferenceTracker tracker(map, params);
    for (const int k : indices) {
      if (reset) tracker.reset();
      const MultiReferenceResult r = tracker.process(frames[static_cast<std::size_t>(k)]);
      if (r.recovery.ran) samples.push_back({order, k, r.recovery.work, r.recovery.cpuMs});
    }
    return samples;
  };
  std::vector<int> inOrder(frames.size());
  std::iota(inOrder.begin(), inOrder.end(), 0);
  std::vector<int> shuffled = inOrder;
  std::mt19937 rng(seed);
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  std::vector<RecoverySample> least;
  for (int repeat = 0; repeat < repeats; ++repeat) {
    std::vector<RecoverySample> samples = play("cold", inOrder, true);
    std::vector<RecoverySample> more = play("shuffled", shuffled, false);
    samples.insert(samples.end(), more.begin(), more.end());
    if (repeat == 0) {
      least = std::move(samples);
      continue;
    }
    // The same recoveries every repeat (the tracker is deterministic); checked all the same.
    if (samples.size() != least.size())
      throw Error("recovery cost: the repeats recovered different frames");
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (samples[i].frame != least[i].frame || samples[i].order != least[i].order)
        throw Error("recovery cost: the repeats recovered different frames");
      least[i].cpuMs = std::min(least[i].cpuMs, samples[i].cpuMs);
    }
  }
  return least;
}

RecoveryCostModel fitRecoveryCostModel(const std::vector<RecoverySample>& samples) {
  if (samples.empty()) throw Error("recovery cost fit: no recovery to fit (no frame was lost)");
  const auto n = static_cast<Eigen::Index>(samples.size());
  Eigen::MatrixXd A(n, kTerms);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    // Relative residuals: each row divided by the recovery's measured cost.
    const RecoverySample& s = samples[static_cast<std::size_t>(i)];
    const double weight = 1.0 / std::max(s.cpuMs, 0.1);
    const auto t = terms(s.work);
    for (int j = 0; j < kTerms; ++j) A(i, j) = weight * t[static_cast<std::size_t>(j)];
    y(i) = weight * s.cpuMs;
  }
  // Exact non-negative least squares for six terms: every subset's unconstrained solution, the
  // best one that is non-negative (the empty subset, all zero, always is).
  std::array<double, kTerms> best{};
  double bestResidual = y.squaredNorm();
  for (int mask = 1; mask < (1 << kTerms); ++mask) {
    std::vector<int> columns;
    for (int j = 0; j < kTerms; ++j)
      if (mask & (1 << j)) columns.push_back(j);
    Eigen::MatrixXd S(n, static_cast<Eigen::Index>(columns.size()));
    for (std::size_t c = 0; c < columns.size(); ++c)
      S.col(static_cast<Eigen::Index>(c)) = A.col(columns[c]);
    const Eigen::VectorXd x = S.colPivHouseholderQr().solve(y);
    if (!x.allFinite() || (x.array() < 0.0).any()) continue;
    const double residual = (S * x - y).squaredNorm();
    if (residual < bestResidual) {
      bestResidual = residual;
      best.fill(0.0);
      for (std::size_t c = 0; c < columns.size(); ++c)
        best[static_cast<std::size_t>(columns[c])] = x(static_cast<Eigen::Index>(c));
    }
  }
  return modelFrom(best);
}

CostModelAgreement agreement(const RecoveryCostModel& model,
                             const std::vector<RecoverySample>& samples) {
  CostModelAgreement a;
  std::vector<double> ratios;
  for (const RecoverySample& s : samples) {
    const double modelled = model.ms(s.work);
    a.modelledSumMs += modelled;
    a.measuredSumMs += s.cpuMs;
    if (s.cpuMs > 0.0) ratios.push_back(modelled / s.cpuMs);
  }
  a.samples = static_cast<int>(samples.size());
  a.sumRatio = a.measuredSumMs > 0.0 ? a.modelledSumMs / a.measuredSumMs : 0.0;
  a.medianRatio = percentile(ratios, 0.5);
  a.p10Ratio = percentile(ratios, 0.1);
  a.p90Ratio = percentile(ratios, 0.9);
  return a;
}

void printRecoveryCostCalibration(const RecoveryCostModel& current, const RecoveryCostModel& fitted,
                                  const std::vector<RecoverySample>& samples, std::FILE* out) {
  std::vector<RecoverySample> cold, shuffled;
  for (const RecoverySample& s : samples) (s.order == "cold" ? cold : shuffled).push_back(s);
  std::fprintf(out, "  %-28s %6s %12s %12s %8s %8s %8s %8s\n", "model / recoveries", "n",
               "modelled ms", "measured ms", "sum", "median", "p10", "p90");
  for (const auto& [name, model] :
       {std::pair<const char*, const RecoveryCostModel&>{"current", current}, {"fitted", fitted}}) {
    std::fprintf(out, "%s (ratios modelled / measured CPU):\n", name);
    printAgreement(out, "cold starts", agreement(model, cold));
    printAgreement(out, "shuffled sequence", agreement(model, shuffled));
    printAgreement(out, "all", agreement(model, samples));
  }
  const auto row = [&](const char* name, double a, double b) {
    std::fprintf(out, "  %-32s %10.3f %10.3f\n", name, a, b);
  };
  std::fprintf(out, "coefficients (ms per unit):          current     fitted\n");
  row("per start pass megapixel", current.msPerStartPassMegapixel, fitted.msPerStartPassMegapixel);
  row("per seeded pass megapixel", current.msPerSeededPassMegapixel,
      fitted.msPerSeededPassMegapixel);
  row("per repeated pass megapixel", current.msPerRepeatedPassMegapixel,
      fitted.msPerRepeatedPassMegapixel);
  row("per detected megapixel", current.msPerDetectedMegapixel, fitted.msPerDetectedMegapixel);
  row("per million comparisons", current.msPerMillionComparisons, fitted.msPerMillionComparisons);
  row("per pose search", current.msPerPoseSearch, fitted.msPerPoseSearch);
}

}  // namespace reftrack::app
