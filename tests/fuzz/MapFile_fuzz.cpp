// libFuzzer target: map.yml (MultiReferenceMap::load, format versions 1-3: `track`, `view`,
// `show-map`, `extend --map`). The folder holds the reference images the seed maps name
// (kImageSize, grey), so a well-formed input gets as far as the full consistency check.
#include <opencv2/imgcodecs.hpp>

#include "FuzzInput.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace {

const cv::Size kImageSize(160, 120);

std::filesystem::path mapFolder() { return reftrack::fuzz::scratchDir() / "map"; }

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::filesystem::create_directories(mapFolder());
  cv::Mat image(kImageSize, CV_8UC1);
  cv::randu(image, 0, 255);
  for (const char* name : {"reference_00.png", "reference_01.png", "reference_02.png",
                           "reference_03.png", "reference_a.png", "reference_b.png"})
    cv::imwrite((mapFolder() / name).string(), image);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  reftrack::fuzz::inputFile("map/map.yml", data, size);
  reftrack::fuzz::expectOnlyReftrackErrors([&] { reftrack::MultiReferenceMap::load(mapFolder()); });
  return 0;
}
