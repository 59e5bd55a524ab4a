// `reftrack params`: every key of the parameter file `--params` accepts (the tracking parameters
// and the viewer's `overlay` section) — dotted name, default, allowed values, one-line meaning —
// from the same fields() lists that read and check them; `--write FILE` writes the defaults as a
// commented YAML file to edit. `reftrack params unprepared` lists (and writes) the section
// `prepare --unprepared --params` reads, which the tracking parameters leave out.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/commands/Commands.hpp"
#include "app/viewer/OverlaySettings.hpp"
#include "engine/config/CommentedParamsFile.hpp"
#include "engine/config/FieldDescriber.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/config/UnpreparedMapParams.hpp"

namespace reftrack::app {

namespace {

struct ParamsOptions {
  std::vector<std::string> filters;  // keys, sections or key names; none: every key
  std::string write;
};

std::vector<ParamDescription> everyParam() {
  std::vector<ParamDescription> keys = describeParams(TrackerParams{});
  const std::vector<ParamDescription> overlay = describeParams(OverlaySettings{});
  keys.insert(keys.end(), overlay.begin(), overlay.end());
  return keys;
}

// Keys of `prepare --unprepared --params` only (not of the tracking parameter file): listed
// when a filter names them.
std::vector<ParamDescription> prepareOnlyParams() { return describeParams(UnpreparedMapParams{}); }

// A key matches its dotted name, its name alone and any section it lies in.
bool matches(const ParamDescription& d, const std::string& filter) {
  return d.key == filter || d.name() == filter || d.key.rfind(filter + ".", 0) == 0;
}

std::vector<ParamDescription> selected(const std::vector<std::string>& filters) {
  std::vector<ParamDescription> keys = everyParam();
  if (filters.empty()) return keys;
  const std::vector<ParamDescription> prepareOnly = prepareOnlyParams();
  keys.insert(keys.end(), prepareOnly.begin(), prepareOnly.end());
  std::erase_if(keys, [&](const ParamDescription& d) {
    return std::none_of(filters.begin(), filters.end(),
                        [&](const std::string& f) { return matches(d, f); });
  });
  return keys;
}

bool isPrepareOnly(const ParamDescription& d) {
  return d.section() == UnpreparedMapParams::kSection;
}

// Throws a usage error naming the nearest key or section when a filter matches nothing.
void checkFilters(const std::vector<std::string>& filters) {
  std::vector<ParamDescription> keys = everyParam();
  const std::vector<ParamDescription> prepareOnly = prepareOnlyParams();
  keys.insert(keys.end(), prepareOnly.begin(), prepareOnly.end());
  std::vector<std::string> names;
  for (const ParamDescription& d : keys) {
    names.push_back(d.key);
    if (!d.section().empty()) names.push_back(d.section());
  }
  for (const std::string& f : filters)
    if (std::none_of(keys.begin(), keys.end(),
                     [&](const ParamDescription& d) { return matches(d, f); }))
      throw CLI::ValidationError("KEY", "no parameter or section '" + f + "' — did you mean '" +
                                            nearestKey(f, names) + "'?");
}

void printTable(const std::vector<ParamDescription>& keys) {
  int keyWidth = 3, valueWidth = 7, allowedWidth = 7;  // "KEY", "DEFAULT", "ALLOWED"
  for (const ParamDescription& d : keys) {
    keyWidth = std::max(keyWidth, static_cast<int>(d.key.size()));
    valueWidth = std::max(valueWidth, static_cast<int>(d.value.size()));
    allowedWidth = std::max(allowedWidth, static_cast<int>(d.allowed.size()));
  }
  if (std::all_of(keys.begin(), keys.end(), isPrepareOnly))
    std::printf(
        "Keys of the parameter file `prepare --unprepared --params` takes (a map from two views\n"
        "and one distance); a key left out keeps its default.\n\n");
  else
    std::printf(
        "Keys of the parameter file `--params` takes (track, view, extend); a key left out keeps\n"
        "its default. `reftrack params --write FILE` writes them as a commented file to edit.\n"
        "`reftrack params unprepared`: the keys of `prepare --unprepared --params`.\n\n");
  std::printf("  %-*s  %-*s  %-*s  %s\n", keyWidth, "KEY", valueWidth, "DEFAULT", allowedWidth,
              "ALLOWED", "MEANING");
  std::string section = "\n";  // none yet
  for (const ParamDescription& d : keys) {
    if (d.section() != section) {
      section = d.section();
      std::printf("\n%s\n", section.empty() ? "(top level)" : (section + ":").c_str());
    }
    std::printf("  %-*s  %-*s  %-*s  %s\n", keyWidth, d.key.c_str(), valueWidth, d.value.c_str(),
                allowedWidth, d.allowed.c_str(), d.help.c_str());
  }
}

void runParams(const ParamsOptions& o) {
  const std::vector<ParamDescription> keys = selected(o.filters);
  if (o.write.empty()) {
    printTable(keys);
    return;
  }
  const bool prepareOnly = std::all_of(keys.begin(), keys.end(), isPrepareOnly);
  writeCommentedParamsFile(
      o.write, keys,
      prepareOnly ? "reftrack " REFTRACK_VERSION
                    " parameters: the defaults, written by `reftrack params --write`.\nThe "
                    "file `prepare --unprepared --params` takes. A key left out keeps its "
                    "default:\nkeep only the keys you change. Each key's comment: its meaning "
                    "(the values allowed)."
                  : "reftrack " REFTRACK_VERSION
                    " parameters: the defaults, written by `reftrack params "
                    "--write`.\nThe file `--params` takes (track, view, extend). A key left out "
                    "keeps its default:\nkeep only the keys you change. Each key's comment: its "
                    "meaning (the values allowed).");
  std::printf("wrote %s: %zu keys, their defaults\n", o.write.c_str(), keys.size());
}

CommandRegistration registerParamsCommand(CLI::App& parent) {
  auto options = std::make_shared<ParamsOptions>();
  CLI::App* sub = parent.add_subcommand(
      "params", "List every parameter key (default, allowed values, meaning) or write them");
  sub->add_option("KEY", options->filters,
                  "only these keys or sections (corners, pose.alpha, min_inliers); default: all")
      ->type_name("KEY|SECTION");
  sub->add_option("--write", options->write,
                  "write the defaults to FILE as commented YAML that `--params` accepts")
      ->type_name("FILE");
  sub->callback([options] {
    checkFilters(options->filters);
    const std::vector<ParamDescription> keys = selected(options->filters);
    if (!options->write.empty() && std::any_of(keys.begin(), keys.end(), isPrepareOnly) &&
        !std::all_of(keys.begin(), keys.end(), isPrepareOnly))
      throw CLI::ValidationError("--write",
                                 "the section unprepared belongs to `prepare --params`, the "
                                 "others to `track/view/extend --params`: write them to two "
                                 "files");
  });
  return {sub, [options] { runParams(*options); }};
}

const CommandRegistrar registrar(80, registerParamsCommand);

}  // namespace

}  // namespace reftrack::app
