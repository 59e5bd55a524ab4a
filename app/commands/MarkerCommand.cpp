// `reftrack marker`: a printable ArUco marker PNG (default DICT_6X6_250 id 23, as the simulator
// and the default MarkerSpec use), with a white quiet zone around it.
#include <cstdio>
#include <memory>
#include <opencv2/aruco.hpp>
#include <opencv2/imgcodecs.hpp>

#include "app/commands/Commands.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"
#include "engine/reference/MarkerSpec.hpp"

namespace reftrack::app {

namespace {

struct MarkerOptions {
  std::string out;
  MarkerSpec spec;
  int pixels = 600, margin = 100;
};

void runMarker(const MarkerOptions& o) {
  o.spec.check();
  const auto dictionary = cv::aruco::getPredefinedDictionary(o.spec.dictionaryEnum());
  cv::Mat marker;
  cv::aruco::drawMarker(dictionary, o.spec.id, o.pixels, marker, 1);
  cv::Mat page(o.pixels + 2 * o.margin, o.pixels + 2 * o.margin, CV_8UC1, cv::Scalar(255));
  marker.copyTo(page(cv::Rect(o.margin, o.margin, o.pixels, o.pixels)));
  writeFileAtomically(o.out, [&](const std::filesystem::path& tmp) {
    if (!cv::imwrite(tmp.string(), page))
      throw Error("cannot write marker image '" + o.out + "' (use a .png name)");
  });
  std::printf("wrote %s: %s id %d, %d px marker with a %d px white margin (%dx%d px)\n",
              o.out.c_str(), o.spec.dictionary.c_str(), o.spec.id, o.pixels, o.margin, page.cols,
              page.rows);
  std::printf(
      "print it so that the black square is exactly the side you give the tracker "
      "(default %.3f m)\n",
      MarkerSpec().sideMetres);
}

CommandRegistration registerMarkerCommand(CLI::App& parent) {
  auto options = std::make_shared<MarkerOptions>();
  CLI::App* sub = parent.add_subcommand("marker", "Write a printable ArUco marker image (PNG)");
  sub->add_option("--out", options->out, "image to write (PNG)")->required();
  sub->add_option("--dictionary", options->spec.dictionary, "ArUco dictionary")
      ->capture_default_str();
  sub->add_option("--id", options->spec.id, "marker id in the dictionary")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--pixels", options->pixels, "side of the marker (black border included), px")
      ->capture_default_str()
      ->check(CLI::Range(16, 20000));
  sub->add_option("--margin", options->margin, "white margin around the marker, px")
      ->capture_default_str()
      ->check(CLI::Range(0, 20000));
  return {sub, [options] { runMarker(*options); }};
}

const CommandRegistrar registrar(90, registerMarkerCommand);

}  // namespace

}  // namespace reftrack::app
