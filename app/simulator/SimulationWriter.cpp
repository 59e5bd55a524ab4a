#include "app/simulator/SimulationWriter.hpp"

#include <cstdio>
#include <future>
#include <opencv2/imgcodecs.hpp>
#include <regex>
#include <string>
#include <vector>

#include "app/cli/Interruption.hpp"
#include "app/cli/ProgressBar.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/TumTrajectory.hpp"

namespace reftrack::app {

namespace fs = std::filesystem;

namespace {

std::string frameName(int k) {
  char name[32];
  std::snprintf(name, sizeof name, "%06d.png", k);
  return name;
}

std::string referenceName(int i) {
  char name[32];
  std::snprintf(name, sizeof name, "reference_%02d.png", i);
  return name;
}

// reference_NN.png of an earlier run with more references.
void removeStaleReferences(const fs::path& dir, int count) {
  static const std::regex form("reference_([0-9]{2})\\.png");
  std::smatch m;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, m, form) && std::stoi(m[1].str()) >= count) {
      std::error_code ec;
      fs::remove(entry.path(), ec);
    }
  }
}

void writePng(const fs::path& file, const cv::Mat& image) {
  // Level 1: noisy frames barely compress further, and encoding dominates the write time.
  const std::vector<int> params = {cv::IMWRITE_PNG_COMPRESSION, 1};
  writeFileAtomically(file, [&](const fs::path& tmp) {
    if (!cv::imwrite(tmp.string(), image, params))
      throw Error("cannot write image '" + file.string() + "'");
  });
}

void makeFolder(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw Error("cannot create output folder '" + dir.string() +
                "': " + (ec ? ec.message() : std::string("a file of that name exists")));
}

// Frames left by an earlier, longer run would not match groundtruth.txt.
void removeStaleFrames(const fs::path& framesDir, int frames) {
  static const std::regex framePattern("([0-9]{6})\\.png");
  for (const fs::directory_entry& entry : fs::directory_iterator(framesDir)) {
    std::smatch m;
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, m, framePattern) && std::stoi(m[1].str()) >= frames)
      fs::remove(entry.path());
  }
}

void writeSceneDescription(const SceneSimulator& sim, const fs::path& file, int frameCount) {
  const SimulationOptions& o = sim.options();
  writeFileAtomically(file, [&](const fs::path& tmp) {
    cv::FileStorage out(tmp.string(), cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
    if (!out.isOpened()) throw Error("cannot write '" + file.string() + "'");
    out << "world_frame"
        << "marker frame: origin at the marker centre, x right, y up on the printed marker, z out "
           "of the desk (desk plane z = 0); metres";
    out << "marker_dictionary" << sim.marker().dictionary;
    out << "marker_id" << sim.marker().id;
    out << "marker_side_m" << sim.marker().sideMetres;
    out << "marker" << sim.marker().toString();
    out << "preset" << o.preset;
    out << "seed" << std::to_string(o.seed);  // text: FileStorage integers are 32-bit
    out << "fps" << o.fps;
    out << "frame_count" << frameCount;
    out << "image_width" << o.size.width << "image_height" << o.size.height;
    out << "fov_deg" << o.fovDeg;
    out << "noise_sigma" << o.noiseSigma;
    out << "motion_blur" << (o.blur ? 1 : 0);
    out << "effects"
        << "{";
    o.effects.write(out);
    out << "}";
    out << "reference_count" << o.referenceCount();
    if (o.referenceBaseline > 0.0) out << "reference_baseline_m" << o.referenceBaseline;
    out << "poses"
        << "groundtruth.txt and references.txt: TUM, camera pose in the world (camera->world)";
    out.release();
  });
}

}  // namespace

void writeSimulation(SceneSimulator& sim, const fs::path& outDir) {
  const SimulationOptions& o = sim.options();
  const fs::path framesDir = outDir / "frames";
  makeFolder(framesDir);
  std::error_code ec;
  fs::remove(outDir / "groundtruth.txt", ec);
  removeStaleFrames(framesDir, o.frames);

  sim.camera().save(outDir / "camera.yml");
  writeSceneDescription(sim, outDir / "scene.yml", o.frames);
  TumTrajectory references;
  const std::vector<RigidPose>& referencePoses = sim.referencePoses();
  for (std::size_t i = 0; i < referencePoses.size(); ++i) {
    references.poses.push_back({static_cast<double>(i), referencePoses[i]});
    const cv::Mat image = sim.renderReferenceView(static_cast<int>(i));
    writePng(outDir / referenceName(static_cast<int>(i)), image);
    if (i < 2) writePng(outDir / (i == 0 ? "reference_a.png" : "reference_b.png"), image);
  }
  removeStaleReferences(outDir, static_cast<int>(referencePoses.size()));
  references.save(outDir / "references.txt");

  // Render frame k (GL, this thread) while frame k-1 is encoded on another thread.
  TumTrajectory groundTruth;
  ProgressBar progress("simulate " + o.preset, static_cast<std::size_t>(o.frames));
  std::future<void> pending;
  // Ctrl-C stops after the frame in hand: the sequence is then complete up to it (scene.yml's
  // frame count and groundtruth.txt say how far).
  const InterruptibleWork interruptible;
  int written = 0;
  for (int k = 0; k < o.frames && !interruptRequested(); ++k, ++written) {
    groundTruth.poses.push_back({k / o.fps, sim.framePose(k)});
    cv::Mat frame = sim.renderFrame(k);
    if (pending.valid()) {
      pending.get();
      progress.advance();
    }
    pending = std::async(std::launch::async, [file = framesDir / frameName(k),
                                              image = std::move(frame)] { writePng(file, image); });
  }
  if (pending.valid()) {
    pending.get();
    progress.advance();
  }
  if (written < o.frames) writeSceneDescription(sim, outDir / "scene.yml", written);
  groundTruth.save(outDir / "groundtruth.txt");
  progress.finish();
}

}  // namespace reftrack::app
