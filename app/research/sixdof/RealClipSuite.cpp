#include "app/research/sixdof/RealClipSuite.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include "app/research/sixdof/FrameOrder.hpp"
#include "engine/config/ConfigFile.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

const std::vector<std::string> kClipKeys = {
    "name",       "folder",     "frames", "camera",   "ground_truth", "first_frame",
    "last_frame", "references", "cube",   "wrong_px", "orders"};

std::string requiredText(const YamlNode& clip, const std::string& key) {
  const YamlNode n = clip[key];
  if (!n.present()) clip.fail(clip.name() + ": '" + key + "' is missing");
  const std::optional<std::string> text = n.text();
  if (!text || text->empty()) n.fail(n.name() + " must be text");
  return *text;
}

// A path inside the data root (or the clip's folder): relative, without "..".
std::filesystem::path relativePath(const YamlNode& clip, const std::string& key,
                                   const std::filesystem::path& fallback) {
  const YamlNode n = clip[key];
  if (!n.present()) return fallback;
  const std::filesystem::path path = requiredText(clip, key);
  if (path.is_absolute())
    n.fail(n.name() + ": '" + path.string() + "' must be relative (to the data root, --data)");
  for (const std::filesystem::path& part : path)
    if (part == "..") n.fail(n.name() + ": '" + path.string() + "' must not leave its folder");
  const std::string text = path.string();
  if (text.rfind("tum:", 0) == 0 || text.rfind("euroc:", 0) == 0)
    n.fail(n.name() + ": an image folder or a video, not a dataset spec");
  return path;
}

int frameIndex(const YamlNode& n) {
  const std::optional<int> v = n.integer();
  if (!v || *v < 0) n.fail(n.name() + " must be a whole number >= 0 (a frame index)");
  return *v;
}

double positive(const YamlNode& n) {
  const std::optional<double> v = n.number();
  if (!v || !std::isfinite(*v) || !(*v > 0)) n.fail(n.name() + " must be a number > 0");
  return *v;
}

void readCube(const YamlNode& clipNode, RealClip& clip) {
  const YamlNode cube = clipNode["cube"];
  if (!cube.present()) clipNode.fail(clipNode.name() + ": 'cube' is missing");
  if (!cube.isMap())
    cube.fail(cube.name() + " must be a map {edge, base_centre} or {edge, in_front_of_reference}");
  requireKnownKeys(cube, {"edge", "base_centre", "in_front_of_reference"});
  const YamlNode edge = cube["edge"];
  if (!edge.present()) cube.fail(cube.name() + ": 'edge' is missing (metres)");
  clip.cubeEdge = positive(edge);
  const YamlNode base = cube["base_centre"], front = cube["in_front_of_reference"];
  if (base.present() == front.present())
    cube.fail(cube.name() +
              ": give one placement, base_centre: [x, y, z] (world, m) or "
              "in_front_of_reference: {distance: M}");
  if (base.present()) {
    if (!base.isList() || base.size() != 3)
      base.fail(base.name() + " must be a list [x, y, z] (world, m)");
    for (std::size_t i = 0; i < 3; ++i) {
      const YamlNode v = base.item(i);
      if (!v.number() || !std::isfinite(*v.number())) v.fail(v.name() + " must be a number");
      clip.cubeBaseCentre[static_cast<Eigen::Index>(i)] = *v.number();
    }
    return;
  }
  if (!front.isMap()) front.fail(front.name() + " must be a map {distance: M}");
  requireKnownKeys(front, {"distance"});
  const YamlNode distance = front["distance"];
  if (!distance.present()) front.fail(front.name() + ": 'distance' is missing (metres)");
  clip.cubeInFrontM = positive(distance);
  if (clip.cubeInFrontM <= 0.5 * clip.cubeEdge)
    distance.fail(distance.name() +
                  " must exceed half the cube's edge (the cube would reach "
                  "behind the camera)");
}

RealClip readClip(const YamlNode& n) {
  if (!n.isMap()) n.fail(n.name() + " must be a map (name, folder, references, cube, ...)");
  requireKnownKeys(n, kClipKeys);
  RealClip clip;
  clip.line = n.line();
  clip.name = requiredText(n, "name");
  for (char c : clip.name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-')
      n["name"].fail(n.name() + ".name: '" + clip.name +
                     "' may hold letters, digits, '.', '_' and '-' only (it names files)");
  if (!n["folder"].present()) n.fail(n.name() + ": 'folder' is missing");
  clip.folder = relativePath(n, "folder", {});
  clip.frames = relativePath(n, "frames", clip.frames);
  clip.camera = relativePath(n, "camera", clip.camera);
  clip.groundTruth = relativePath(n, "ground_truth", clip.groundTruth);
  if (n["first_frame"].present()) clip.firstFrame = frameIndex(n["first_frame"]);
  if (n["last_frame"].present()) {
    clip.lastFrame = frameIndex(n["last_frame"]);
    if (*clip.lastFrame < clip.firstFrame)
      n["last_frame"].fail(n.name() + ".last_frame " + std::to_string(*clip.lastFrame) +
                           " is before first_frame " + std::to_string(clip.firstFrame));
  }
  const YamlNode refs = n["references"];
  if (!refs.present()) n.fail(n.name() + ": 'references' is missing");
  if (!refs.isList() || refs.size() < 2)
    refs.fail(refs.name() + " must be a list of two or more frame indices, e.g. [0, 40]");
  std::set<int> seen;
  for (const YamlNode& r : refs.children()) {
    const int frame = frameIndex(r);
    if (!seen.insert(frame).second)
      r.fail(r.name() + ": frame " + std::to_string(frame) + " given twice");
    const bool inside = frame >= clip.firstFrame && (!clip.lastFrame || frame <= *clip.lastFrame);
    if (!inside)
      r.fail(r.name() + ": reference frame " + std::to_string(frame) +
             " is outside the clip's frames " + std::to_string(clip.firstFrame) + ".." +
             (clip.lastFrame ? std::to_string(*clip.lastFrame) : std::string("the last")));
    clip.references.push_back(frame);
  }
  readCube(n, clip);
  if (!n["wrong_px"].present()) n.fail(n.name() + ": 'wrong_px' is missing (px)");
  clip.wrongPx = positive(n["wrong_px"]);
  if (const YamlNode orders = n["orders"]; orders.present()) {
    if (!orders.isList() || orders.size() == 0)
      orders.fail(orders.name() + " must be a list of one or more frame orders, e.g. [sequence]");
    for (const YamlNode& o : orders.children()) {
      if (!o.text()) o.fail(o.name() + " must be an order's name, e.g. shuffled-sequence");
      clip.orders.push_back(*o.text());
    }
    try {
      const std::vector<FrameOrder> parsed = parseFrameOrders(clip.orders);
      clip.orders.clear();
      for (const FrameOrder& order : parsed) {
        if (order.kind == FrameOrderKind::Away)
          throw Error(order.name + ": the suite plays no other scene (away:N)");
        if (clip.lastFrame)  // a return: order's ranges within the clip's frames
          planFrames(order, clip.frameCount(), 1);
        clip.orders.push_back(order.name);
      }
    } catch (const Error& e) {
      orders.fail(orders.name() + ": " + e.what());
    }
  }
  return clip;
}

}  // namespace

const RealClip* RealClipSuite::find(const std::string& name) const {
  for (const RealClip& clip : clips)
    if (clip.name == name) return &clip;
  return nullptr;
}

namespace {

RealClipSuite readSuite(const YamlNode& root, const std::string& what) {
  RealClipSuite suite;
  suite.description = what;
  try {
    requireKnownKeys(root, {"clips"});
    const YamlNode clips = root["clips"];
    if (!clips.present()) root.fail("the suite has no 'clips' list");
    if (!clips.isList() || clips.size() == 0)
      clips.fail("'clips' must be a list of one or more clips");
    for (const YamlNode& n : clips.children()) {
      RealClip clip = readClip(n);
      if (const RealClip* twin = suite.find(clip.name))
        n["name"].fail(n.name() + ".name: '" + clip.name + "' is the name of the clip on line " +
                       std::to_string(twin->line) + " too");
      suite.clips.push_back(std::move(clip));
    }
  } catch (const Error& e) {
    throw Error(what + ": " + e.what());
  }
  return suite;
}

}  // namespace

RealClipSuite parseRealClipSuite(const std::string& text, const std::string& what) {
  return readSuite(readConfigText(text, what), what);
}

RealClipSuite loadRealClipSuite(const std::filesystem::path& file) {
  const std::string what = "suite file '" + file.string() + "'";
  if (!std::filesystem::exists(file)) throw Error(what + " not found");
  return readSuite(readConfigFile(file, what), what);
}

}  // namespace reftrack::app
