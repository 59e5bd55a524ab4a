#include "app/research/sixdof/GroundTruthBenchmarkReport.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <iomanip>

#include "app/plot/PlotCanvas.hpp"
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

// "ORB+PnP+Kalman" -> "orb_pnp_kalman".
std::string columnName(const MethodRun& run) {
  std::string name;
  for (char c : run.method)
    name += std::isalnum(static_cast<unsigned char>(c))
                ? static_cast<char>(std::tolower(static_cast<unsigned char>(c)))
                : '_';
  return name + (run.shuffled ? "_shuffled_px" : "_sequence_px");
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

const cv::Scalar kColours[] = {{200, 90, 20},  {30, 30, 210},  {40, 160, 40},
                               {150, 40, 150}, {20, 150, 200}, {90, 90, 90}};

}  // namespace

std::string groundTruthBenchmarkTable(const GroundTruthBenchmarkResult& r) {
  std::string out;
  const int truthFrames = static_cast<int>(std::count(r.truth.begin(), r.truth.end(), true));
  out += textf("frames: %d of %s (%dx%d), %d with a true pose (%s)\n", r.frames,
               r.framesDescription.c_str(), r.frameSize.width, r.frameSize.height, truthFrames,
               r.groundTruthDescription.c_str());
  out += "references: frames";
  for (std::size_t i = 0; i < r.references.size(); ++i)
    out += textf(" %d (%.1f mm from the first)", r.references[i], r.referenceDistancesMm[i]);
  out +=
      textf("\nreftrack map: %d points; keypoint layer %d keypoints, %d of them with a 3D point\n",
            r.mapPoints, r.mapKeypoints, r.mapKeypointPoints);
  if (!r.modelPoints.empty()) {
    out += "peers' triangulated points:";
    for (std::size_t i = 0; i < r.modelPoints.size(); ++i)
      out +=
          textf("%s %s %d", i ? "," : "", r.modelPoints[i].first.c_str(), r.modelPoints[i].second);
    out += "\n";
  }
  out += textf(
      "cube: base centre (%.3f, %.3f, %.3f) m, edge %.3f m; error: mean distance of its 8 "
      "vertices projected with K alone, estimated vs true pose (px)\n",
      r.cubeCentre.x(), r.cubeCentre.y(), r.cubeCentre.z(), r.cubeEdge);
  out += textf(
      "shuffled: every frame a cold start, order seed %llu; CPU: thread time per frame, one "
      "thread, %d pass(es); cpu_x: median / reftrack's in the same order\n",
      static_cast<unsigned long long>(r.shuffleSeed), r.passes);
  out += textf("%-15s %-8s %7s %7s %6s %8s %8s %8s %5s %7s %10s %6s\n", "method", "order", "frames",
               "posed", "cover%", "mean_px", "p95_px", "max_px", ">5px", "<=1.5px", "cpu_ms_med",
               "cpu_x");
  for (const MethodRun& run : r.runs) {
    const MethodSummary s = summarise(run, r.truth);
    double reftrackCpu = NAN;
    for (const MethodRun& other : r.runs)
      if (other.method == "reftrack" && other.shuffled == run.shuffled)
        reftrackCpu = summarise(other, r.truth).cpuMedianMs;
    out += textf("%-15s %-8s %7d %7d %6.1f %8s %8s %8s %5d %7d %10.2f %6s\n", run.method.c_str(),
                 run.shuffled ? "shuffled" : "sequence", s.frames, s.posed, s.coveragePercent(),
                 cell(s.meanPx, 3).c_str(), cell(s.p95Px, 3).c_str(), cell(s.maxPx, 2).c_str(),
                 s.wrong, s.good, s.cpuMedianMs, cell(s.cpuMedianMs / reftrackCpu, 2).c_str());
  }
  for (const MethodRun& run : r.runs) {
    const int behind = summarise(run, r.truth).behind;
    if (behind > 0)
      out += textf(
          "%s %s: %d pose(s) put the whole cube behind the camera (counted in >5px, not in "
          "mean_px, p95_px, max_px)\n",
          run.method.c_str(), run.shuffled ? "shuffled" : "sequence", behind);
  }
  for (const MethodRun& run : r.runs) {
    const PredictionSummary p = summarisePrediction(run, r.truth);
    if (p.frames == 0) continue;
    out += textf(
        "predicted cube error, %s %s (issue 32): median %s, p95 %s, max %s px over %d frames; "
        "true / predicted median %s (quartiles %s-%s); uncertain %d (their true error mean %s "
        "px); >5px and not uncertain %d\n",
        run.method.c_str(), run.shuffled ? "shuffled" : "sequence",
        cell(p.predictedMedianPx, 3).c_str(), cell(p.predictedP95Px, 3).c_str(),
        cell(p.predictedMaxPx, 3).c_str(), p.frames, cell(p.ratioMedian, 2).c_str(),
        cell(p.ratioP25, 2).c_str(), cell(p.ratioP75, 2).c_str(), p.uncertain,
        cell(p.uncertainTrueMeanPx, 2).c_str(), p.wrongNotUncertain);
  }
  for (const MethodRun& run : r.runs)
    for (const auto& [reason, frames] : run.noPose)
      out += textf("no pose, %s %s: %d x %s\n", run.method.c_str(),
                   run.shuffled ? "shuffled" : "sequence", frames, reason.c_str());
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
    for (int k = 0; k < r.frames; ++k) {
      out << k << ',' << (r.truth[static_cast<std::size_t>(k)] ? 1 : 0);
      for (const MethodRun& run : r.runs) {
        out << ',';
        const double e = run.errorPx[static_cast<std::size_t>(k)];
        if (!std::isnan(e)) out << e;
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

void writeGroundTruthBenchmarkPlot(const GroundTruthBenchmarkResult& r,
                                   const std::filesystem::path& png) {
  PlotCanvas plot(textf("Cube error per frame, sequence order (%d frames; above %.0f px drawn at "
                        "%.0f; gaps: no pose)",
                        r.frames, kPlotErrorCapPx, kPlotErrorCapPx),
                  "frame", "mean cube vertex error (px)", cv::Size(1200, 600));
  std::size_t colour = 0;
  for (const MethodRun& run : r.runs) {
    if (run.shuffled) continue;
    std::vector<double> x, y;
    for (int k = 0; k < r.frames; ++k) {
      x.push_back(k);
      y.push_back(std::min(run.errorPx[static_cast<std::size_t>(k)], kPlotErrorCapPx));
    }
    const MethodSummary summary = summarise(run, r.truth);
    plot.addLine(textf("%s (%.1f%% posed)", run.method.c_str(), summary.coveragePercent()), x, y,
                 kColours[colour++ % std::size(kColours)]);
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
