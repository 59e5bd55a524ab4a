#include "app/research/sixdof/GroundTruthBenchmarkReport.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <iomanip>

#include "app/plot/PlotCanvas.hpp"
#include "app/research/sixdof/RealFootageBenchmark.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

std::string textf(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

std::string textf(const char* fmt, ...) {
  char buffer[1024];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buffer, sizeof buffer, fmt, args);
  va_end(args);
  return buffer;
}

// "ORB+PnP+Kalman" in cuts:8 -> "orb_pnp_kalman_cuts:8_px".
std::string columnName(const MethodRun& run) {
  std::string name;
  for (char c : run.method)
    name += std::isalnum(static_cast<unsigned char>(c))
                ? static_cast<char>(std::tolower(static_cast<unsigned char>(c)))
                : '_';
  return name + "_" + run.order.name + "_px";
}

// "reftrack_sequence_predicted_px".
std::string predictedColumnName(const MethodRun& run) {
  std::string name = columnName(run);
  return name.substr(0, name.size() - 3) + "_predicted_px";
}

// A number, or "-" when there is none.
std::string cell(double value, int decimals) {
  return std::isnan(value) ? std::string("-") : textf("%.*f", decimals, value);
}

// What an order plays, for the table's header ("" for the sequence order).
std::string describe(const FrameOrder& order, int frames) {
  switch (order.kind) {
    case FrameOrderKind::Sequence:
      return "";
    case FrameOrderKind::Shuffled:
      return "shuffled: every frame a cold start";
    case FrameOrderKind::ShuffledSequence:
      return "shuffled-sequence: the shuffled order as one sequence, no reset";
    case FrameOrderKind::Cuts:
      return textf("%s: %d segments of about %d frames in a shuffled order, one sequence, no reset",
                   order.name.c_str(), order.count, frames / std::max(order.count, 1));
    case FrameOrderKind::Stride:
      return textf("%s: frames 0, %d, %d, ... in order, one sequence (only those scored)",
                   order.name.c_str(), order.count, 2 * order.count);
    case FrameOrderKind::Away:
      return textf("%s: in order, %d frames of another scene after frame %d, one sequence",
                   order.name.c_str(), order.count, frames / 2 - 1);
    case FrameOrderKind::Return:
      return textf(
          "%s: the ranges of frames one after the other, one sequence, no reset (the first: the "
          "start, the last: the return; scored per play)",
          order.name.c_str());
  }
  return "";
}

// Per peer in reftrack's orders with cold starts or an other scene: the frames the peer posed
// within kWrongPosePx and reftrack did not (with the first few frame indices), and the reverse.
std::string reacquiredLines(const GroundTruthBenchmarkResult& r) {
  std::string out;
  for (const MethodRun& ours : r.runs) {
    if (ours.method != "reftrack") continue;
    if (!ours.plan.coldStarts && ours.order.kind != FrameOrderKind::Away) continue;
    for (const MethodRun& peer : r.runs) {
      if (peer.method == "reftrack" || peer.order.name != ours.order.name) continue;
      std::vector<int> onlyPeer;
      int onlyOurs = 0;
      for (std::size_t k = 0; k < r.truth.size() && k < ours.errorPx.size(); ++k) {
        const bool peerGood = peer.errorPx[k] <= kWrongPosePx;
        const bool oursGood = ours.errorPx[k] <= kWrongPosePx;
        if (peerGood && !oursGood) onlyPeer.push_back(r.firstFrame + static_cast<int>(k));
        onlyOurs += oursGood && !peerGood ? 1 : 0;
      }
      std::string frames;
      for (std::size_t i = 0; i < onlyPeer.size() && i < 12; ++i)
        frames += (i ? ", " : " (frames ") + std::to_string(onlyPeer[i]);
      if (!onlyPeer.empty()) frames += onlyPeer.size() > 12 ? ", ...)" : ")";
      out += textf(
          "%s order: %zu frames posed within %.0f px by %s but not by reftrack%s; %d by "
          "reftrack but not by %s\n",
          ours.order.name.c_str(), onlyPeer.size(), kWrongPosePx, peer.method.c_str(),
          frames.c_str(), onlyOurs, peer.method.c_str());
    }
  }
  return out;
}

// One line of an away:N run: poses while away (all wrong), the CPU spent there (mean per frame
// and its share of one core at the sequence's frame rate) and how the method came back.
std::string awayLine(const MethodRun& run, double fps, const std::string& scene) {
  const AwayReturn back = awayReturn(run);
  double sum = 0.0;
  for (double ms : run.awayCpuMs) sum += ms;
  const double mean = run.awayCpuMs.empty() ? NAN : sum / static_cast<double>(run.awayCpuMs.size());
  std::vector<double> cpu = run.awayCpuMs;
  return textf(
      "%s %s (%s): %d posed while away (target 0); CPU while away mean %s ms per frame = %s%% of "
      "one core at %.0f fps (median %s ms); after the return: first pose within %.1f px %s, %d "
      "wrong\n",
      run.method.c_str(), run.order.name.c_str(), scene.c_str(), run.awayPosed,
      cell(mean, 2).c_str(), cell(mean * fps / 10.0, 1).c_str(), fps,
      cell(percentileOf(cpu, 0.5), 2).c_str(), kGoodPosePx,
      back.framesToReacquire < 0 ? "never"
                                 : textf("after %d frames", back.framesToReacquire).c_str(),
      back.wrongAfter);
}

}  // namespace

std::string stopLines(const std::vector<MethodRun>& runs, const std::string& prefix) {
  std::string out;
  const auto breakdown = [](const std::map<std::string, int>& stops) {
    std::string text;
    for (const auto& [stage, n] : stops)
      text += textf("%s%s %d", text.empty() ? "" : ", ", stage.c_str(), n);
    return text;
  };
  for (const MethodRun& run : runs) {
    if (!run.startStops.empty())
      out +=
          textf("%s%s %s: per frame not tracked, the start near a reference: %s\n", prefix.c_str(),
                run.method.c_str(), run.order.name.c_str(), breakdown(run.startStops).c_str());
    if (!run.searchStops.empty()) {
      std::vector<double> cpu = run.searchCpuMs;
      out += textf(
          "%s%s %s: relocalisation attempts, what stopped each: %s; thread CPU per attempt with "
          "its verification: median %s ms\n",
          prefix.c_str(), run.method.c_str(), run.order.name.c_str(),
          breakdown(run.searchStops).c_str(), cell(percentileOf(cpu, 0.5), 1).c_str());
    }
  }
  return out;
}

std::string returnLines(const MethodRun& run, double fps, double wrongPx, int firstFrame) {
  const std::vector<RangeOutcome> ranges = rangeOutcomes(run, wrongPx);
  if (ranges.empty()) return "";
  std::string out = textf(
      "%s %s: per range (frames %d on): posed, within %.0f px, wrong (> %g px), the first pose "
      "within %.0f px after k frames, CPU mean per frame:",
      run.method.c_str(), run.order.name.c_str(), firstFrame, kWrongPosePx, wrongPx, kWrongPosePx);
  int awayFrames = 0, awayPosed = 0, awayWrong = 0;
  double awayCpu = 0.0;
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const RangeOutcome& o = ranges[i];
    out += textf("%s %d-%d %d/%d %d %d k=%s %s ms", i ? ";" : "", o.range.first, o.range.last,
                 o.posed, o.frames, o.within, o.wrong,
                 o.framesToReacquire < 0 ? "never" : std::to_string(o.framesToReacquire).c_str(),
                 cell(o.cpuMeanMs, 2).c_str());
    if (i == 0 || i + 1 == ranges.size()) continue;
    awayFrames += o.range.size();
    awayPosed += o.posed;
    awayWrong += o.wrong;
    if (!std::isnan(o.cpuMeanMs)) awayCpu += o.cpuMeanMs * o.range.size();
  }
  const RangeOutcome& back = ranges.back();
  out += "\n";
  out += textf(
      "%s %s: between the start and the return %d frames, %d posed, %d wrong (target 0); CPU "
      "mean %s ms per frame = %s%% of one core at %.0f fps; the return: first pose within %.0f "
      "px %s, %d wrong\n",
      run.method.c_str(), run.order.name.c_str(), awayFrames, awayPosed, awayWrong,
      cell(awayFrames ? awayCpu / awayFrames : NAN, 2).c_str(),
      cell(awayFrames ? awayCpu / awayFrames * fps / 10.0 : NAN, 1).c_str(), fps, kWrongPosePx,
      back.framesToReacquire < 0 ? "never"
                                 : textf("after %d frames", back.framesToReacquire).c_str(),
      back.wrong);
  return out;
}

namespace {

// One line of a cuts:N run: per cut its position, the frames either side, the frames needed to
// re-acquire (k) and the wrong poses until the next cut; then the worst.
std::string cutsLine(const MethodRun& run, int firstFrame) {
  const std::vector<CutRecovery> cuts = cutRecoveries(run);
  std::string out = textf(
      "%s %s: per cut @position frame->frame: re-acquired within k frames (<= %.1f px), wrong "
      "(> %.0f px) until the next cut:",
      run.method.c_str(), run.order.name.c_str(), kGoodPosePx, kWrongPosePx);
  int worst = 0, wrong = 0, never = 0;
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    const CutRecovery& c = cuts[i];
    out += textf("%s @%zu %d->%d k=%s wrong=%d", i ? "," : "", c.position, firstFrame + c.fromFrame,
                 firstFrame + c.toFrame,
                 c.framesToReacquire < 0 ? textf("never(%d)", c.segmentFrames).c_str()
                                         : std::to_string(c.framesToReacquire).c_str(),
                 c.wrong);
    worst = std::max(worst, c.framesToReacquire);
    never += c.framesToReacquire < 0 ? 1 : 0;
    wrong += c.wrong;
  }
  const std::string maxK = never > 0
                               ? textf("never (%d of %zu cuts not re-acquired)", never, cuts.size())
                               : std::to_string(worst);
  out += textf("; max k=%s, %d wrong after the cuts (target: 0 wrong, every k <= 1)\n",
               maxK.c_str(), wrong);
  return out;
}

const cv::Scalar kColours[] = {{200, 90, 20},  {30, 30, 210},  {40, 160, 40},
                               {150, 40, 150}, {20, 150, 200}, {90, 90, 90}};

}  // namespace

bool usesMap(const GroundTruthBenchmarkResult& r) {
  return std::any_of(r.runs.begin(), r.runs.end(), [](const MethodRun& run) {
    return run.method == "reftrack" || run.method == "ORB+PnP+Kalman";
  });
}

std::string cubeDescription(const GroundTruthBenchmarkResult& r) {
  if (r.cubeInFrontM <= 0)
    return textf("base centre (%.3f, %.3f, %.3f) m, edge %.3f m", r.cubeCentre.x(),
                 r.cubeCentre.y(), r.cubeCentre.z(), r.cubeEdge);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : r.cube) centre += v / static_cast<double>(r.cube.size());
  return textf(
      "centred %.3f m in front of reference frame %d's camera on its optical axis, edges along "
      "its axes (centre (%.3f, %.3f, %.3f) m in the world), edge %.3f m",
      r.cubeInFrontM, r.firstFrame + (r.references.empty() ? 0 : r.references.front()), centre.x(),
      centre.y(), centre.z(), r.cubeEdge);
}

std::string groundTruthBenchmarkTable(const GroundTruthBenchmarkResult& r) {
  std::string out;
  const int truthFrames = static_cast<int>(std::count(r.truth.begin(), r.truth.end(), true));
  const std::string range =
      r.firstFrame > 0 ? textf(" (%d-%d)", r.firstFrame, r.firstFrame + r.frames - 1) : "";
  out += textf("frames: %d%s of %s (%dx%d), %d with a true pose (%s)\n", r.frames, range.c_str(),
               r.framesDescription.c_str(), r.frameSize.width, r.frameSize.height, truthFrames,
               r.groundTruthDescription.c_str());
  out += "references: frames";
  for (std::size_t i = 0; i < r.references.size(); ++i)
    out += textf(" %d (%.1f mm from the first)", r.firstFrame + r.references[i],
                 r.referenceDistancesMm[i]);
  if (!usesMap(r))
    out += "\nreftrack map: not prepared (neither reftrack nor the Kalman baseline ran)\n";
  else if (r.mapError.empty())
    out += textf(
        "\nreftrack map: %d points; keypoint layer %d keypoints, %d of them with a 3D point\n",
        r.mapPoints, r.mapKeypoints, r.mapKeypointPoints);
  else
    out += "\nreftrack map: none, the preparation refused it: " + r.mapError + "\n";
  if (!r.modelPoints.empty()) {
    out += "peers' triangulated points:";
    for (std::size_t i = 0; i < r.modelPoints.size(); ++i)
      out +=
          textf("%s %s %d", i ? "," : "", r.modelPoints[i].first.c_str(), r.modelPoints[i].second);
    out += "\n";
  }
  out += "cube: " + cubeDescription(r) +
         "; error: mean distance of its 8 vertices projected with K alone, estimated vs true "
         "pose (px)\n";
  std::string orders;
  bool shuffles = false;
  for (const FrameOrder& order : r.orders) {
    const std::string what = describe(order, r.frames);
    if (!what.empty()) orders += (orders.empty() ? "" : "; ") + what;
    shuffles = shuffles ||
               (order.kind != FrameOrderKind::Sequence && order.kind != FrameOrderKind::Stride);
  }
  if (shuffles)
    orders += textf(", order seed %llu", static_cast<unsigned long long>(r.shuffleSeed));
  if (!orders.empty()) out += orders + "; ";
  out += textf(
      "CPU: thread time per frame, one thread, %d pass(es); cpu_x: median / reftrack's in the "
      "same order\n",
      r.passes);
  int orderWidth = 8;
  for (const FrameOrder& order : r.orders)
    orderWidth = std::max(orderWidth, static_cast<int>(order.name.size()));
  out += textf("%-15s %-*s %7s %7s %6s %8s %8s %8s %5s %7s %10s %6s\n", "method", orderWidth,
               "order", "frames", "posed", "cover%", "mean_px", "p95_px", "max_px", ">5px",
               "<=1.5px", "cpu_ms_med", "cpu_x");
  for (const MethodRun& run : r.runs) {
    const MethodSummary s = summarise(run, r.truth);
    double reftrackCpu = NAN;
    for (const MethodRun& other : r.runs)
      if (other.method == "reftrack" && other.order.name == run.order.name)
        reftrackCpu = summarise(other, r.truth).cpuMedianMs;
    out += textf("%-15s %-*s %7d %7d %6.1f %8s %8s %8s %5d %7d %10.2f %6s\n", run.method.c_str(),
                 orderWidth, run.order.name.c_str(), s.frames, s.posed, s.coveragePercent(),
                 cell(s.meanPx, 3).c_str(), cell(s.p95Px, 3).c_str(), cell(s.maxPx, 2).c_str(),
                 s.wrong, s.good, s.cpuMedianMs, cell(s.cpuMedianMs / reftrackCpu, 2).c_str());
  }
  for (const MethodRun& run : r.runs)
    if (run.order.kind == FrameOrderKind::Cuts) out += cutsLine(run, r.firstFrame);
  for (const MethodRun& run : r.runs)
    if (run.order.kind == FrameOrderKind::Away) out += awayLine(run, r.fps, r.awayDescription);
  for (const MethodRun& run : r.runs) out += returnLines(run, r.fps, kWrongPosePx, r.firstFrame);
  out += reacquiredLines(r);
  for (const MethodRun& run : r.runs) {
    const int behind = summarise(run, r.truth).behind;
    if (behind > 0)
      out += textf(
          "%s %s: %d pose(s) put the whole cube behind the camera (counted in >5px, not in "
          "mean_px, p95_px, max_px)\n",
          run.method.c_str(), run.order.name.c_str(), behind);
  }
  for (const MethodRun& run : r.runs) {
    const PredictionSummary p = summarisePrediction(run, r.truth);
    if (p.frames == 0) continue;
    out += textf(
        "predicted cube error, %s %s (issue 32): median %s, p95 %s, max %s px over %d frames; "
        "true / predicted median %s (quartiles %s-%s); uncertain %d (their true error mean %s "
        "px); >5px and not uncertain %d\n",
        run.method.c_str(), run.order.name.c_str(), cell(p.predictedMedianPx, 3).c_str(),
        cell(p.predictedP95Px, 3).c_str(), cell(p.predictedMaxPx, 3).c_str(), p.frames,
        cell(p.ratioMedian, 2).c_str(), cell(p.ratioP25, 2).c_str(), cell(p.ratioP75, 2).c_str(),
        p.uncertain, cell(p.uncertainTrueMeanPx, 2).c_str(), p.wrongNotUncertain);
  }
  out += stopLines(r.runs, "");
  for (const MethodRun& run : r.runs)
    for (const auto& [reason, frames] : run.noPose)
      out += textf("no pose, %s %s: %d x %s\n", run.method.c_str(), run.order.name.c_str(), frames,
                   reason.c_str());
  out += textf("benchmark time: %.1f s (preparation and every run, wall clock)\n", r.seconds);
  return out;
}

void writeGroundTruthBenchmarkCsv(const GroundTruthBenchmarkResult& r,
                                  const std::filesystem::path& csv) {
  writeFileAtomically(csv, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp);
    if (!out) throw Error("cannot write '" + csv.string() + "'");
    out << "frame,true_pose";
    for (const MethodRun& run : r.runs) out << ',' << columnName(run);
    for (const MethodRun& run : r.runs)  // the predicted error (reftrack), after the errors
      if (!run.predictedErrorPx.empty()) out << ',' << predictedColumnName(run);
    out << '\n' << std::setprecision(8);
    std::vector<std::vector<bool>> played;
    for (const MethodRun& run : r.runs) played.push_back(playedFrames(run.plan, r.frames));
    for (int k = 0; k < r.frames; ++k) {
      const std::size_t frame = static_cast<std::size_t>(k);
      out << r.firstFrame + k << ',' << (r.truth[frame] ? 1 : 0);
      for (std::size_t i = 0; i < r.runs.size(); ++i) {
        out << ',';
        const double e = r.runs[i].errorPx[frame];
        if (played[i][frame] && !std::isnan(e)) out << e;
      }
      for (const MethodRun& run : r.runs) {
        if (run.predictedErrorPx.empty()) continue;
        out << ',';
        const double p = run.predictedErrorPx[static_cast<std::size_t>(k)];
        if (!std::isnan(p)) out << p;
      }
      out << '\n';
    }
    if (!out.flush()) throw Error("cannot write '" + csv.string() + "'");
  });
}

std::optional<std::size_t> bestPeerRun(const GroundTruthBenchmarkResult& r,
                                       const std::string& order) {
  std::optional<std::size_t> best;
  MethodSummary bestSummary;
  const auto better = [](const MethodSummary& a, const MethodSummary& b) {
    const bool aFull = a.coveragePercent() >= 90.0, bFull = b.coveragePercent() >= 90.0;
    if (aFull != bFull) return aFull;
    if (aFull && !std::isnan(a.meanPx) && !std::isnan(b.meanPx) && a.meanPx != b.meanPx)
      return a.meanPx < b.meanPx;
    return a.posed > b.posed;
  };
  for (std::size_t i = 0; i < r.runs.size(); ++i) {
    const MethodRun& run = r.runs[i];
    if (run.method == "reftrack" || run.order.name != order) continue;
    const MethodSummary summary = summarise(run, r.truth);
    if (!best || better(summary, bestSummary)) {
      best = i;
      bestSummary = summary;
    }
  }
  return best;
}

void writeGroundTruthBenchmarkPlot(const GroundTruthBenchmarkResult& r,
                                   const std::filesystem::path& png) {
  const std::string order = r.orders.empty() ? std::string("sequence") : r.orders.front().name;
  std::vector<std::size_t> drawn;
  for (std::size_t i = 0; i < r.runs.size(); ++i)
    if (r.runs[i].method == "reftrack" && r.runs[i].order.name == order) drawn.push_back(i);
  const std::optional<std::size_t> peer = bestPeerRun(r, order);
  if (peer) drawn.push_back(*peer);
  if (drawn.empty())  // no reftrack run: the first method's
    for (std::size_t i = 0; i < r.runs.size() && drawn.empty(); ++i)
      if (r.runs[i].order.name == order) drawn.push_back(i);
  std::vector<MethodSummary> summaries;
  double p95 = 0.0;
  for (std::size_t i : drawn) {
    summaries.push_back(summarise(r.runs[i], r.truth));
    if (std::isfinite(summaries.back().p95Px)) p95 = std::max(p95, summaries.back().p95Px);
  }
  const double cap = std::clamp(std::ceil(1.5 * p95), kPlotErrorCapMinPx, kPlotErrorCapMaxPx);
  const std::string versus =
      peer ? textf(": reftrack vs %s, the best peer", r.runs[*peer].method.c_str()) : "";
  PlotCanvas plot(textf("Cube error per frame, %s order%s", order.c_str(), versus.c_str()),
                  r.firstFrame > 0 ? textf("frame (%d-%d; gaps: no pose)", r.firstFrame,
                                           r.firstFrame + r.frames - 1)
                                   : textf("frame (%d; gaps: no pose)", r.frames),
                  textf("mean cube vertex error, px (above %.0f drawn at %.0f)", cap, cap),
                  cv::Size(1200, 600));
  for (std::size_t d = 0; d < drawn.size(); ++d) {
    const MethodRun& run = r.runs[drawn[d]];
    const std::vector<bool> played = playedFrames(run.plan, r.frames);
    std::vector<double> x, y;
    for (int k = 0; k < r.frames; ++k) {
      if (!played[static_cast<std::size_t>(k)]) continue;
      x.push_back(r.firstFrame + k);
      y.push_back(std::min(run.errorPx[static_cast<std::size_t>(k)], cap));
    }
    plot.addLine(textf("%s (%.1f%% posed, mean %.3f px)", run.method.c_str(),
                       summaries[d].coveragePercent(), summaries[d].meanPx),
                 x, y, kColours[d % std::size(kColours)]);
  }
  plot.save(png);
}

GroundTruthBenchmarkFiles writeGroundTruthBenchmarkFiles(const GroundTruthBenchmarkResult& r,
                                                         const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec || !std::filesystem::is_directory(folder))
    throw Error("cannot create the output folder '" + folder.string() + "'");
  GroundTruthBenchmarkFiles files{folder / "table.txt", folder / "cube_errors.csv",
                                  folder / "cube_errors.png"};
  const std::string table = groundTruthBenchmarkTable(r);
  writeFileAtomically(files.table, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp);
    out << table;
    if (!out.flush()) throw Error("cannot write '" + files.table.string() + "'");
  });
  writeGroundTruthBenchmarkCsv(r, files.csv);
  writeGroundTruthBenchmarkPlot(r, files.plot);
  return files;
}

}  // namespace reftrack::app
