#pragma once
// PeerPoseCache (`bench-real --suite --peer-cache DIR`): a folder of per-frame peers' poses
// (PeerPoses), one text file per peer and clip, named by a hash of everything those poses depend
// on (the key): the frame files' names, sizes and modification times, the references (input frame
// indices) and their true poses, the camera, the detector and PerFramePnpPeer's parameters,
// OpenCV's version and kPeerPoseCacheVersion. The file holds the key itself, compared whole on
// reading, so a hash collision or a stale file never gives another input's poses; a file under
// another key, or one that cannot be read, is recomputed and rewritten (atomically). Poses are
// written with 17 significant digits: read back bit for bit.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/research/baselines/PerFramePnpPeer.hpp"
#include "app/research/sixdof/PerFramePeerPoses.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack::app {

// Bump when the peers' code (PerFramePnpPeer, computePeerPoses) changes the poses they give.
inline constexpr int kPeerPoseCacheVersion = 1;

// Everything a per-frame peer's poses over a range of frames depend on.
struct PeerPoseInputs {
  std::string detector;                           // sift, akaze, orb
  std::vector<std::filesystem::path> frameFiles;  // the files the frames are read from
  std::vector<int> references;                    // input frame indices
  std::vector<RigidPose> referencePoses;          // their true world->camera poses
  PinholeCamera camera;
  PerFramePnpPeerParams params;
};

// The key: one line per input above (file names without their folder, so the same files under
// another data root share it). Throws reftrack::Error when a frame file cannot be examined.
std::string peerPoseCacheKey(const PeerPoseInputs& inputs);

// The files frames firstFrame .. firstFrame + frames - 1 of `input` are read from (frames 0: to
// the end): an image folder's or glob's images, or a video file itself. Throws reftrack::Error for
// other inputs (tum:, euroc:) and for a range beyond a folder's images.
std::vector<std::filesystem::path> frameFilesOf(const std::string& input, int firstFrame,
                                                int frames);

class PeerPoseCache {
 public:
  explicit PeerPoseCache(std::filesystem::path folder);  // the folder is made when first stored

  const std::filesystem::path& folder() const { return folder_; }
  // DIR/<detector>-<16 hex digits of the key's FNV-1a hash>.txt
  std::filesystem::path fileFor(const std::string& detector, const std::string& key) const;
  // The poses stored under `key`, or nullopt with `why` (none stored, stored under another key,
  // unreadable).
  std::optional<PeerPoses> load(const std::string& detector, const std::string& key,
                                std::string& why) const;
  // Writes atomically; throws reftrack::Error when the folder or file cannot be written.
  void store(const std::string& detector, const std::string& key, const PeerPoses& poses) const;
  // The stored poses of `inputs`, else compute() stored and returned; `why` says where they came
  // from ("cached in FILE", or why they were computed).
  PeerPoses getOrCompute(const PeerPoseInputs& inputs, const std::function<PeerPoses()>& compute,
                         bool& fromCache, std::string& why) const;

 private:
  std::filesystem::path folder_;
};

}  // namespace reftrack::app
