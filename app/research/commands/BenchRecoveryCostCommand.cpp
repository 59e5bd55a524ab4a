// `reftrack bench-recovery-cost`: re-measures the recovery's cost model (the milliseconds the
// relocalisation budget is charged per unit of counted work on recorded input,
// engine/relocalisation/RecoveryWork) on this machine: a map's frames played cold and as a
// shuffled sequence, one thread, every recovery's counted work against its CPU time; prints how
// the current model and the least-squares fit agree with the measured cost, and the fitted
// coefficients.
#include <cstdio>
#include <fstream>
#include <memory>
#include <opencv2/core/utility.hpp>
#include <string>
#include <vector>

#include "app/cli/ProgressBar.hpp"
#include "app/commands/Commands.hpp"
#include "app/research/relocalisation/RecoveryCostCalibration.hpp"
#include "app/sources/FrameSourceFactory.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {

namespace {

struct Args {
  std::vector<std::filesystem::path> maps;
  std::vector<std::string> inputs;
  std::filesystem::path params, csv;
  int frames = 0;
  unsigned seed = 1;
  int repeats = 3;
};

CommandRegistration registerBenchRecoveryCostCommand(CLI::App& parent) {
  auto args = std::make_shared<Args>();
  CLI::App* sub = parent.add_subcommand(
      "bench-recovery-cost",
      "The recovery's cost model (budget on recorded input) against measured CPU time");
  sub->add_option("--map", args->maps, "Map folder (`reftrack prepare`); repeated: pooled")
      ->required()
      ->check(CLI::ExistingDirectory);
  sub->add_option("--input", args->inputs,
                  "Frames of the map's scene (as `track --input`), one per --map")
      ->required();
  sub->add_option("--frames", args->frames, "The first N frames (0: all)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  sub->add_option("--params", args->params, "TrackerParams YAML")->check(CLI::ExistingFile);
  sub->add_option("--shuffle-seed", args->seed, "Seed of the shuffled order")
      ->capture_default_str();
  sub->add_option("--repeats", args->repeats,
                  "Plays of both orders; each recovery keeps its least CPU time")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  sub->add_option("--csv", args->csv, "Write one row per recovery: its work and measured CPU");
  sub->footer(
      "Every frame is recovered twice: as a cold start (the tracker reset before it) and in a\n"
      "shuffled order played as one sequence (every frame a jump), with a budget no recovery\n"
      "comes near, --repeats times: each recovery keeps its least CPU time (the work is the\n"
      "same every time). One thread (cv::setNumThreads(1)); CPU time of the process.\n"
      "Several --map/--input pairs pool their recoveries into one fit. The fit is per\n"
      "keypoint kind (the maps'): put its coefficients in\n"
      "RecoveryCostModel::defaults (engine/relocalisation/RecoveryWork.cpp).");
  return {
      sub, [args] {
        cv::setNumThreads(1);
        if (args->maps.size() != args->inputs.size())
          throw CLI::ValidationError("--input", "give one --input per --map");
        TrackerParams params =
            args->params.empty() ? TrackerParams{} : TrackerParams::load(args->params);
        params.mode = TrackingMode::SixDof;
        params.check();
        std::vector<RecoverySample> samples;
        for (std::size_t c = 0; c < args->maps.size(); ++c) {
          const std::string& input = args->inputs[c];
          const MultiReferenceMap map = MultiReferenceMap::load(args->maps[c]);
          std::unique_ptr<render::GlContext> gl;
          if (isSimulatorInput(input)) gl = render::createHeadlessContext();
          std::unique_ptr<FrameSource> source = openFrameSource(input);
          std::vector<cv::Mat> frames;
          while (args->frames == 0 || static_cast<int>(frames.size()) < args->frames) {
            std::optional<Frame> f = source->next();
            if (!f) break;
            if (f->image.size() != map.camera.imageSize())
              throw Error("frame " + std::to_string(f->index) + " of '" + input +
                          "' is not of the map's size");
            frames.push_back(std::move(f->image));
          }
          if (frames.empty()) throw Error("input '" + input + "' gave no frames");
          std::printf("%s: %zu frames, keypoints %s; playing them cold and shuffled...\n",
                      input.c_str(), frames.size(), params.relocalisation.keypoints.c_str());
          std::fflush(stdout);
          for (RecoverySample& s :
               collectRecoverySamples(map, frames, params, args->seed, args->repeats)) {
            s.clip = static_cast<int>(c);
            samples.push_back(std::move(s));
          }
        }
        const RecoveryCostModel current =
            RecoveryCostModel::defaults(params.relocalisation.keypoints);
        const RecoveryCostModel fitted = fitRecoveryCostModel(samples);
        printRecoveryCostCalibration(current, fitted, samples, stdout);
        if (!args->csv.empty()) {
          writeFileAtomically(args->csv, [&](const std::filesystem::path& tmp) {
            std::ofstream out(tmp);
            out << "clip,order,frame,start_pass_mpx,seeded_pass_mpx,repeated_pass_mpx,detected_mpx,"
                   "comparisons_millions,pose_searches,cpu_ms,current_ms,fitted_ms\n";
            for (const RecoverySample& s : samples)
              out << s.clip << ',' << s.order << ',' << s.frame << ',' << s.work.startPassMegapixels
                  << ',' << s.work.seededPassMegapixels << ',' << s.work.repeatedPassMegapixels
                  << ',' << s.work.keypoints.detectedMegapixels << ','
                  << s.work.keypoints.comparisonsMillions << ',' << s.work.keypoints.poseSearches
                  << ',' << s.cpuMs << ',' << current.ms(s.work) << ',' << fitted.ms(s.work)
                  << '\n';
            if (!out) throw Error("cannot write '" + args->csv.string() + "'");
          });
          std::printf("per recovery: %s\n", args->csv.string().c_str());
        }
      }};
}

const CommandRegistrar registrar(87, registerBenchRecoveryCostCommand, CommandGroup::Research);

}  // namespace

}  // namespace reftrack::app
