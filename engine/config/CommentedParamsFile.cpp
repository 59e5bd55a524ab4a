#include "engine/config/CommentedParamsFile.hpp"

#include <fstream>
#include <sstream>

#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

std::vector<std::string> sectionPath(const ParamDescription& d) {
  std::vector<std::string> path;
  std::istringstream in(d.section());
  for (std::string part; std::getline(in, part, '.');) path.push_back(part);
  return path;
}

void writeComment(std::ostream& out, const std::string& indent, const std::string& text) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    out << indent << (line.empty() ? "#" : "# " + line) << "\n";
}

}  // namespace

std::string commentedParamsYaml(const std::vector<ParamDescription>& keys,
                                const std::string& heading) {
  std::ostringstream out;
  writeComment(out, "", heading);
  std::vector<std::string> open;  // the sections the previous key was in
  bool first = true;
  for (const ParamDescription& d : keys) {
    const std::vector<std::string> path = sectionPath(d);
    std::size_t same = 0;
    while (same < open.size() && same < path.size() && open[same] == path[same]) ++same;
    if (first || same < path.size() || open.size() != path.size()) {
      if (first || same == 0) out << "\n";  // a blank line before each top-level section
      for (std::size_t level = same; level < path.size(); ++level)
        out << std::string(2 * level, ' ') << path[level] << ":\n";
    }
    open = path;
    first = false;
    const std::string indent(2 * path.size(), ' ');
    std::string comment = d.help;
    if (!d.allowed.empty()) comment += (comment.empty() ? "(" : " (") + d.allowed + ")";
    writeComment(out, indent, comment);
    out << indent << d.name() << ": " << d.value << "\n";
  }
  return out.str();
}

void writeCommentedParamsFile(const std::filesystem::path& file,
                              const std::vector<ParamDescription>& keys,
                              const std::string& heading) {
  const std::string text = commentedParamsYaml(keys, heading);
  const std::string what = "cannot write parameter file '" + file.string() + "'";
  if (std::filesystem::is_directory(file)) throw Error(what + ": it is a folder");
  try {
    writeFileAtomically(file, [&](const std::filesystem::path& tmp) {
      std::ofstream out(tmp, std::ios::binary);
      if (!out) throw Error("cannot create a file in its folder");
      out << text;
      out.close();
      if (!out) throw Error("writing failed (disk full?)");
    });
  } catch (const Error& e) {
    throw Error(what + ": " + e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    throw Error(what + ": " + e.code().message());
  }
}

}  // namespace reftrack
