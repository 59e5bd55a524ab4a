// `reftrack experiment-reference-pair`: what limits the map of two references of a recording with
// ground truth (ReferencePairExperiment.hpp): the given poses against the images (SIFT matches'
// epipolar distances), the map `prepare` builds and its time, and its points' error in other
// true-posed frames beside points triangulated from the SIFT matches.
#include "app/commands/Commands.hpp"
#include "app/research/preparation/ReferencePairExperiment.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

CommandRegistration registerExperimentReferencePairCommand(CLI::App& parent) {
  CLI::App* sub = parent.add_subcommand(
      "experiment-reference-pair",
      "The map of two references of a recording with ground truth: pose consistency, map, "
      "accuracy in other frames");
  struct Options {
    ReferencePairExperimentOptions experiment;
    std::vector<int> refs;
    std::filesystem::path prepareParams;
  };
  auto o = std::make_shared<Options>();
  sub->add_option("--input", o->experiment.sequence.input,
                  "Image folder (frame k at k / 30 s), video, tum:DIR or euroc:DIR")
      ->required();
  sub->add_option("--camera", o->experiment.sequence.camera, "camera.yml");
  sub->add_option("--gt", o->experiment.sequence.groundTruth,
                  "TUM trajectory (camera in world), tum:DIR or euroc:DIR");
  sub->add_option("--ref-frames", o->refs, "The two reference frames, e.g. 200,220")
      ->delimiter(',')
      ->expected(2)
      ->required();
  sub->add_option("--check-frames", o->experiment.checkFrames,
                  "Frames the map's points are looked for in (true poses), e.g. 190,210,230")
      ->delimiter(',');
  sub->add_option("--prepare-params", o->prepareParams, "`prepare --params` YAML")
      ->check(CLI::ExistingFile);
  sub->add_option("--search-radius", o->experiment.searchRadiusPx,
                  "Search radius around each projection in a check frame (px)")
      ->check(CLI::Range(2, 64))
      ->capture_default_str();
  return {sub, [o] {
            o->experiment.refA = o->refs.at(0);
            o->experiment.refB = o->refs.at(1);
            if (!o->prepareParams.empty())
              o->experiment.prepare = ReferencePreparerParams::load(o->prepareParams);
            runReferencePairExperiment(o->experiment);
          }};
}

const CommandRegistrar registrar(75, registerExperimentReferencePairCommand,
                                 CommandGroup::Research);

}  // namespace

}  // namespace reftrack::app
