#include "app/research/sixdof/RealClipSuiteReport.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>

#include "app/research/sixdof/GroundTruthBenchmarkReport.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

std::string textf(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

std::string textf(const char* fmt, ...) {
  char buffer[2048];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buffer, sizeof buffer, fmt, args);
  va_end(args);
  return buffer;
}

std::string cell(double value, int decimals) {
  return std::isnan(value) ? std::string("-") : textf("%.*f", decimals, value);
}

// Posed frames with a true pose within `within` px and more than `wrong` px off (those behind the
// camera are wrong).
std::pair<int, int> withinAndWrong(const MethodRun& run, const std::vector<bool>& truth,
                                   double within, double wrong) {
  int good = 0, bad = 0;
  for (const double e : scoredErrors(run, truth)) {
    if (std::isnan(e)) continue;
    good += e <= within ? 1 : 0;
    bad += e > wrong ? 1 : 0;
  }
  return {good, bad};
}

std::string orderLegend(const std::vector<std::string>& orders, std::uint64_t seed) {
  std::string out;
  for (const FrameOrder& order : parseFrameOrders(orders)) {
    std::string what;
    switch (order.kind) {
      case FrameOrderKind::Sequence:
        what = "every frame in order";
        break;
      case FrameOrderKind::Shuffled:
        what = "every frame in a shuffled order, each a cold start (reset before it)";
        break;
      case FrameOrderKind::ShuffledSequence:
        what =
            "the frames in a shuffled order played as one sequence, no reset (every frame a "
            "jump)";
        break;
      case FrameOrderKind::Cuts:
        what = textf("%d contiguous segments in a shuffled order, one sequence", order.count);
        break;
      case FrameOrderKind::Stride:
        what = textf("every %d-th frame in order, one sequence (only those scored)", order.count);
        break;
      case FrameOrderKind::Away:
        what = "in order with another scene in the middle";
        break;
      case FrameOrderKind::Return:
        what =
            "the ranges of the clip's frames one after the other, one sequence (the start, away, "
            "the return; scored per play)";
        break;
    }
    out += (out.empty() ? "" : "; ") + order.name + ": " + what;
  }
  return out + textf(" (shuffle seed %llu)", static_cast<unsigned long long>(seed));
}

std::string clipLegend(const RealClipRun& c) {
  const GroundTruthBenchmarkResult& r = c.benchmark;
  const int truth = static_cast<int>(std::count(r.truth.begin(), r.truth.end(), true));
  std::string refs;
  for (std::size_t i = 0; i < r.references.size(); ++i)
    refs += textf("%s%d", i ? ", " : "", r.firstFrame + r.references[i]);
  const double apart = r.referenceDistancesMm.size() > 1 ? r.referenceDistancesMm[1] : NAN;
  std::string out = textf(
      "%s: frames %d-%d (%d with a true pose), %dx%d; references %s (%s mm apart); cube %s; "
      "wrong: > %g px\n",
      c.clip.name.c_str(), r.firstFrame, r.firstFrame + r.frames - 1, truth, r.frameSize.width,
      r.frameSize.height, refs.c_str(), cell(apart, 1).c_str(), cubeDescription(r).c_str(),
      c.clip.wrongPx);
  out += "  ";
  if (!usesMap(r))
    out += "no reftrack map (reftrack did not run)";
  else if (r.mapError.empty())
    out += textf("reftrack map %d points (keypoint layer: %d with a 3D point)", r.mapPoints,
                 r.mapKeypointPoints);
  else
    out += "reftrack map: none, the preparation refused it (" + r.mapError + ")";
  if (!r.modelPoints.empty()) {
    out += "; peers' triangulated points:";
    for (std::size_t i = 0; i < r.modelPoints.size(); ++i)
      out +=
          textf("%s %s %d", i ? "," : "", r.modelPoints[i].first.c_str(), r.modelPoints[i].second);
    out += c.peerSources.empty() ? ""
           : c.peersFromCache    ? " (poses from the cache)"
                                 : " (poses computed)";
  }
  return out + "\n";
}

std::string ratioLine(const std::string& lead, const SuiteRatio& w) {
  const std::string ours = std::isnan(w.reftrackMeanPx) ? std::string("posed no frame")
                                                        : textf("mean %.3f px", w.reftrackMeanPx);
  return textf("%s %s (%s): reftrack %s / its best peer %s %.3f px = %s\n", lead.c_str(),
               w.clip.c_str(), w.order.c_str(), ours.c_str(), w.peer.c_str(), w.peerMeanPx,
               std::isinf(w.ratio) ? "inf" : textf("%.2f", w.ratio).c_str());
}

}  // namespace

std::vector<SuiteRatio> suiteRatios(const RealClipSuiteResult& result) {
  std::vector<SuiteRatio> ratios;
  for (const RealClipRun& c : result.clips) {
    const GroundTruthBenchmarkResult& r = c.benchmark;
    for (const FrameOrder& order : r.orders) {
      const std::optional<std::size_t> peer = bestPeerRun(r, order.name);
      if (!peer) continue;
      const MethodSummary theirs = summarise(r.runs[*peer], r.truth);
      for (const MethodRun& run : r.runs) {
        if (run.method != "reftrack" || run.order.name != order.name) continue;
        if (std::isnan(theirs.meanPx)) continue;
        const MethodSummary ours = summarise(run, r.truth);
        SuiteRatio s;
        s.clip = c.clip.name;
        s.order = order.name;
        s.peer = r.runs[*peer].method;
        s.wrongPx = c.clip.wrongPx;
        s.reftrackMeanPx = ours.meanPx;
        s.peerMeanPx = theirs.meanPx;
        s.ratio = std::isnan(ours.meanPx) ? INFINITY : ours.meanPx / theirs.meanPx;
        ratios.push_back(s);
      }
    }
  }
  return ratios;
}

std::optional<SuiteRatio> worstRatio(const std::vector<SuiteRatio>& ratios,
                                     const std::string& order, double maxWrongPx) {
  std::optional<SuiteRatio> worst;
  for (const SuiteRatio& s : ratios)
    if ((order.empty() || s.order == order) && s.wrongPx <= maxWrongPx &&
        (!worst || s.ratio > worst->ratio))
      worst = s;
  return worst;
}

std::string realClipSuiteTable(const RealClipSuiteResult& result) {
  std::string out =
      textf("suite: %s, data %s; %zu clip(s) run, %zu skipped\n", result.suiteDescription.c_str(),
            result.dataRoot.string().c_str(), result.clips.size(), result.skipped.size());
  for (const std::string& s : result.skipped) out += "skipped: " + s + "\n";
  for (const RealClipRun& c : result.clips) out += clipLegend(c);
  const std::uint64_t seed = result.clips.empty() ? 1 : result.clips.front().benchmark.shuffleSeed;
  out += "orders: " + orderLegend(result.orders, seed) + "\n";
  out += result.peerCache
             ? "per-frame peers (SIFT/AKAZE/ORB+PnP): each clip's frames given a pose once, in "
               "order, by each peer, and those poses reused in every order (a per-frame peer gives "
               "a frame the same pose in any order), from the peer cache when cached there (their "
               "ms/frame are then those of the run that filled it)\n"
             : "per-frame peers (SIFT/AKAZE/ORB+PnP): each clip's frames given a pose once, in "
               "order, by each peer, and those poses reused in every order (a per-frame peer gives "
               "a frame the same pose in any order)\n";
  out +=
      "columns: tracked = frames given a pose (posed%: of the frames with a true pose); mean_px, "
      "p95_px: cube error of the posed frames (8 vertices through K alone; wrong poses "
      "included); <=5px: posed within 5 px; wrong: posed more than the clip's >px off; "
      "true/pred: reftrack's median true / predicted cube error (-: no prediction); ms/frame: "
      "median thread CPU per frame, one thread\n";
  int clipWidth = 4, orderWidth = 5;
  for (const RealClipRun& c : result.clips)
    clipWidth = std::max(clipWidth, static_cast<int>(c.clip.name.size()));
  for (const std::string& o : result.orders)
    orderWidth = std::max(orderWidth, static_cast<int>(o.size()));
  out += textf("%-*s %-*s %-15s %6s %7s %6s %8s %8s %6s %5s %4s %9s %8s\n", clipWidth, "clip",
               orderWidth, "order", "method", "frames", "tracked", "posed%", "mean_px", "p95_px",
               "<=5px", "wrong", ">px", "true/pred", "ms/frame");
  for (const RealClipRun& c : result.clips) {
    const GroundTruthBenchmarkResult& r = c.benchmark;
    for (const FrameOrder& order : r.orders)
      for (const MethodRun& run : r.runs) {
        if (run.order.name != order.name) continue;
        const MethodSummary s = summarise(run, r.truth);
        const auto [within, wrong] = withinAndWrong(run, r.truth, kWrongPosePx, c.clip.wrongPx);
        const PredictionSummary p = summarisePrediction(run, r.truth);
        // reftrack (or the Kalman baseline) without its map ran nothing: no time to show.
        const bool ranNothing =
            !r.mapError.empty() && (run.method == "reftrack" || run.method == "ORB+PnP+Kalman");
        out += textf("%-*s %-*s %-15s %6d %7d %6.1f %8s %8s %6d %5d %4g %9s %8s\n", clipWidth,
                     c.clip.name.c_str(), orderWidth, order.name.c_str(), run.method.c_str(),
                     s.frames, s.posed, s.coveragePercent(), cell(s.meanPx, 3).c_str(),
                     cell(s.p95Px, 3).c_str(), within, wrong, c.clip.wrongPx,
                     cell(p.frames > 0 ? p.ratioMedian : NAN, 2).c_str(),
                     cell(ranNothing ? NAN : s.cpuMedianMs, 2).c_str());
      }
  }
  for (const RealClipRun& c : result.clips) {
    for (const MethodRun& run : c.benchmark.runs)
      out += returnLines(run, c.benchmark.fps, c.clip.wrongPx, c.benchmark.firstFrame);
    out += stopLines(c.benchmark.runs, c.clip.name + ": ");
  }
  const std::vector<SuiteRatio> ratios = suiteRatios(result);
  const std::optional<SuiteRatio> worst = worstRatio(ratios);
  if (!worst) return out + "worst clip: no clip has both a reftrack run and a peer with a mean\n";
  if (result.orders.size() > 1)
    for (const std::string& order : result.orders)
      if (const std::optional<SuiteRatio> w = worstRatio(ratios, order))
        out += ratioLine("worst clip in " + order + " order:", *w);
  const std::optional<SuiteRatio> subPixel = worstRatio(ratios, "", kWrongPosePx);
  if (subPixel && subPixel->clip != worst->clip)
    out += ratioLine(textf("worst clip with a sub-pixel truth (wrong_px <= %g):", kWrongPosePx),
                     *subPixel);
  return out + ratioLine("worst clip:", *worst);
}

RealClipSuiteFiles writeRealClipSuiteFiles(const RealClipSuiteResult& result,
                                           const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec || !std::filesystem::is_directory(folder))
    throw Error("cannot create the output folder '" + folder.string() + "'");
  RealClipSuiteFiles files;
  for (const RealClipRun& c : result.clips) {
    files.clipDirs.push_back(folder / c.clip.name);
    writeGroundTruthBenchmarkFiles(c.benchmark, files.clipDirs.back());
  }
  files.table = folder / "table.txt";
  const std::string table = realClipSuiteTable(result);
  writeFileAtomically(files.table, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp);
    out << table;
    if (!out.flush()) throw Error("cannot write '" + files.table.string() + "'");
  });
  return files;
}

}  // namespace reftrack::app
