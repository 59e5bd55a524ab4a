#include "app/research/sixdof/PeerPoseCache.hpp"

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <opencv2/core/version.hpp>
#include <sstream>

#include "app/sources/ImageFolderSource.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace fs = std::filesystem;

namespace {

// A new field of the peer's parameters must join the key (below) before this size changes.
static_assert(sizeof(PerFramePnpPeerParams) == 48,
              "a new PerFramePnpPeerParams field must join peerPoseCacheKey");

constexpr const char* kFileHeader =
    "reftrack per-frame peer poses (bench-real --suite --peer-cache)";

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// R row by row, then t: 12 numbers that give the pose back bit for bit.
std::string poseNumbers(const RigidPose& T) {
  std::string out = number(T.rotation()(0, 0));
  for (int i = 1; i < 9; ++i) out.append(" ").append(number(T.rotation()(i / 3, i % 3)));
  for (int i = 0; i < 3; ++i) out.append(" ").append(number(T.translation()(i)));
  return out;
}

// Text kept on one line of the file.
std::string oneLine(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

// FNV-1a, 64 bits: a stable file name for the key (the key itself is compared on reading).
std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

bool isImageInput(const std::string& input) {
  return fs::is_directory(input) || input.find_first_of("*?[") != std::string::npos;
}

}  // namespace

std::vector<fs::path> frameFilesOf(const std::string& input, int firstFrame, int frames) {
  if (input.rfind("tum:", 0) == 0 || input.rfind("euroc:", 0) == 0)
    throw Error("the peer cache takes an image folder or a video, not '" + input + "'");
  if (!isImageInput(input)) {
    if (!fs::is_regular_file(input)) throw Error("input '" + input + "' not found");
    return {fs::path(input)};  // a video: the whole file
  }
  const ImageFolderSource folder(input);
  const std::vector<fs::path>& all = folder.files();
  const std::size_t first = static_cast<std::size_t>(std::max(firstFrame, 0));
  const std::size_t end = frames > 0 ? first + static_cast<std::size_t>(frames) : all.size();
  if (first >= all.size() || end > all.size())
    throw Error(folder.description() + " holds " + std::to_string(all.size()) + " images: frames " +
                std::to_string(first) + " .. " + std::to_string(end - 1) + " are not all there");
  return {all.begin() + static_cast<std::ptrdiff_t>(first),
          all.begin() + static_cast<std::ptrdiff_t>(end)};
}

std::string peerPoseCacheKey(const PeerPoseInputs& in) {
  if (in.references.size() != in.referencePoses.size())
    throw Error("peer cache: " + std::to_string(in.references.size()) + " references and " +
                std::to_string(in.referencePoses.size()) + " poses");
  std::string key = "version " + std::to_string(kPeerPoseCacheVersion) + ", OpenCV " + CV_VERSION +
                    "\ndetector " + in.detector + "\n";
  const PerFramePnpPeerParams& p = in.params;
  key += "params orb_features " + std::to_string(p.orbFeatures) + " ratio_test " +
         number(p.ratioTest) + " max_triangulation_error_px " + number(p.maxTriangulationErrorPx) +
         " ransac_iterations " + std::to_string(p.ransacIterations) +
         " ransac_error_px_at_640x480 " + number(p.ransacErrorPxAt640x480) + " ransac_confidence " +
         number(p.ransacConfidence) + " min_inliers " + std::to_string(p.minInliers) + "\n";
  const cv::Size size = in.camera.imageSize();
  key += "camera " + std::to_string(size.width) + "x" + std::to_string(size.height) + " K";
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) key.append(" ").append(number(in.camera.K()(r, c)));
  key += " distortion";
  for (double d : in.camera.distortion()) key.append(" ").append(number(d));
  key += "\n";
  for (std::size_t i = 0; i < in.references.size(); ++i)
    key += "reference " + std::to_string(in.references[i]) + " " +
           poseNumbers(in.referencePoses[i]) + "\n";
  key += "frame files " + std::to_string(in.frameFiles.size()) + "\n";
  for (const fs::path& file : in.frameFiles) {
    std::error_code ec;
    const std::uintmax_t bytes = fs::file_size(file, ec);
    if (ec) throw Error("peer cache: cannot examine the frame file '" + file.string() + "'");
    const fs::file_time_type modified = fs::last_write_time(file, ec);
    if (ec) throw Error("peer cache: cannot examine the frame file '" + file.string() + "'");
    key += file.filename().string() + " " + std::to_string(bytes) + " " +
           std::to_string(modified.time_since_epoch().count()) + "\n";
  }
  return key;
}

PeerPoseCache::PeerPoseCache(fs::path folder) : folder_(std::move(folder)) {}

fs::path PeerPoseCache::fileFor(const std::string& detector, const std::string& key) const {
  char hash[24];
  std::snprintf(hash, sizeof hash, "%016" PRIx64, fnv1a(key));
  return folder_ / (detector + "-" + hash + ".txt");
}

std::optional<PeerPoses> PeerPoseCache::load(const std::string& detector, const std::string& key,
                                             std::string& why) const {
  const fs::path file = fileFor(detector, key);
  std::ifstream in(file);
  if (!in) {
    why = "none cached";
    return std::nullopt;
  }
  const auto unreadable = [&](const std::string& what) {
    why = "the cached '" + file.string() + "' is unreadable (" + what + ")";
    return std::nullopt;
  };
  std::string line;
  if (!std::getline(in, line) || line != kFileHeader) return unreadable("not a peer-pose file");
  int keyLines = -1;
  if (!std::getline(in, line) || std::sscanf(line.c_str(), "key-lines %d", &keyLines) != 1 ||
      keyLines < 0)
    return unreadable("no key");
  std::string stored;
  for (int i = 0; i < keyLines; ++i) {
    if (!std::getline(in, line)) return unreadable("the key is cut short");
    stored += line + "\n";
  }
  if (stored != key) {
    why = "the cached '" + file.string() + "' is for other inputs";
    return std::nullopt;
  }
  PeerPoses poses;
  int frames = -1;
  if (!std::getline(in, line) || line.rfind("method ", 0) != 0) return unreadable("no method");
  poses.method = line.substr(7);
  if (!std::getline(in, line) ||
      std::sscanf(line.c_str(), "model_points %d", &poses.modelPoints) != 1)
    return unreadable("no model_points");
  if (!std::getline(in, line) || line.rfind("model_error", 0) != 0)
    return unreadable("no model_error");
  poses.modelError = line.size() > 12 ? line.substr(12) : "";
  if (!std::getline(in, line) || std::sscanf(line.c_str(), "frames %d", &frames) != 1 || frames < 0)
    return unreadable("no frame count");
  poses.poses.resize(static_cast<std::size_t>(frames));
  poses.reasons.resize(static_cast<std::size_t>(frames));
  poses.cpuMs.assign(static_cast<std::size_t>(frames), 0.0);
  for (int k = 0; k < frames; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    if (!std::getline(in, line)) return unreadable("frame " + std::to_string(k) + " is missing");
    std::istringstream fields(line);
    int index = -1;
    std::string kind, cpu;
    fields >> index >> kind >> cpu;
    char* end = nullptr;
    poses.cpuMs[i] = std::strtod(cpu.c_str(), &end);
    if (index != k || cpu.empty() || *end != '\0')
      return unreadable("frame " + std::to_string(k) + " is not in order");
    if (kind == "none") {
      std::getline(fields >> std::ws, poses.reasons[i]);
      continue;
    }
    if (kind != "pose") return unreadable("frame " + std::to_string(k) + ": '" + kind + "'");
    double v[12];
    for (double& x : v) {
      std::string text;
      fields >> text;
      x = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0')
        return unreadable("frame " + std::to_string(k) + ": a bad number");
    }
    Eigen::Matrix3d R;
    R << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
    poses.poses[i] = RigidPose(R, Eigen::Vector3d(v[9], v[10], v[11]));
  }
  if (!std::getline(in, line) || line != "end") return unreadable("no end line");
  why = "cached in '" + file.string() + "'";
  return poses;
}

void PeerPoseCache::store(const std::string& detector, const std::string& key,
                          const PeerPoses& poses) const {
  std::error_code ec;
  fs::create_directories(folder_, ec);
  if (ec || !fs::is_directory(folder_))
    throw Error("cannot create the peer cache folder '" + folder_.string() + "'");
  const fs::path file = fileFor(detector, key);
  int keyLines = 0;
  for (char c : key) keyLines += c == '\n' ? 1 : 0;
  writeFileAtomically(file, [&](const fs::path& tmp) {
    std::ofstream out(tmp);
    out << kFileHeader << "\nkey-lines " << keyLines << "\n"
        << key << "method " << oneLine(poses.method) << "\nmodel_points " << poses.modelPoints
        << "\nmodel_error " << oneLine(poses.modelError) << "\nframes " << poses.poses.size()
        << "\n";
    for (std::size_t k = 0; k < poses.poses.size(); ++k) {
      out << k << (poses.poses[k] ? " pose " : " none ") << number(poses.cpuMs.at(k));
      if (poses.poses[k])
        out << " " << poseNumbers(*poses.poses[k]);
      else
        out << " " << oneLine(poses.reasons.at(k));
      out << "\n";
    }
    out << "end\n";
    if (!out.flush()) throw Error("cannot write the peer cache file '" + file.string() + "'");
  });
}

PeerPoses PeerPoseCache::getOrCompute(const PeerPoseInputs& inputs,
                                      const std::function<PeerPoses()>& compute, bool& fromCache,
                                      std::string& why) const {
  const std::string key = peerPoseCacheKey(inputs);
  if (std::optional<PeerPoses> cached = load(inputs.detector, key, why)) {
    fromCache = true;
    return *cached;
  }
  fromCache = false;
  PeerPoses poses = compute();
  store(inputs.detector, key, poses);
  why += "; computed and stored in '" + fileFor(inputs.detector, key).string() + "'";
  return poses;
}

}  // namespace reftrack::app
