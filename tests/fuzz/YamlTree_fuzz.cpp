// libFuzzer target: the YAML reader every user file goes through (ConfigFile: yaml-cpp's parser
// and YamlTree's checks), then every node read every way a reader reads one: key lookup,
// children, numbers, integers, booleans, text and OpenCV matrices (YamlMatrix).
#include <vector>

#include "FuzzInput.hpp"
#include "engine/config/ConfigFile.hpp"
#include "engine/config/YamlMatrix.hpp"

namespace {

// Iterative (the depth is the input's); each node once per path, at most 100000 paths, since an
// alias may stand for a node again and again.
void readEveryNode(const reftrack::YamlNode& root) {
  std::vector<reftrack::YamlNode> pending{root};
  for (int visited = 0; !pending.empty() && visited < 100000; ++visited) {
    const reftrack::YamlNode node = pending.back();
    pending.pop_back();
    (void)node.number();
    (void)node.integer();
    (void)node.boolean();
    (void)node.text();
    (void)node["dt"].present();
    if (node.isMap())
      reftrack::fuzz::expectOnlyReftrackErrors([&] { (void)reftrack::readYamlMatrix(node); });
    for (const reftrack::YamlNode& child : node.children()) pending.push_back(child);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  reftrack::fuzz::expectOnlyReftrackErrors(
      [&] { readEveryNode(reftrack::readConfigText(reftrack::fuzz::text(data, size), "input")); });
  return 0;
}
