#include "engine/config/ConfigFile.hpp"

#include <fstream>
#include <iterator>
#include <memory>

#include "engine/config/YamlTree.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

YamlNode readConfigText(const std::string& text, const std::string& what,
                        const std::string& invalid) {
  std::shared_ptr<const YamlTree> tree;
  try {
    tree = std::make_shared<const YamlTree>(parseYamlTree(text));
  } catch (const Error& e) {
    throw Error(what + " " + invalid + ": " + e.what());
  }
  const YamlNode root(tree);
  if (!root.isMap() && !root.isNull())
    throw Error(what + " must hold a map of key: value at the top level (line " +
                std::to_string(root.line()) + ")");
  return root;
}

YamlNode readConfigFile(const std::filesystem::path& file, const std::string& what,
                        const std::string& invalid) {
  if (std::filesystem::is_directory(file)) throw Error(what + " is a folder, not a file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(what + " cannot be read");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw Error(what + " cannot be read");
  return readConfigText(text, what, invalid);
}

}  // namespace reftrack
