#pragma once
// PerFramePeerPoses: a per-frame OpenCV peer (PerFramePnpPeer: SIFT, AKAZE or ORB + PnP from the
// reference frames) run once over every frame of a GroundTruthSequence, in frame order. The peer
// keeps nothing from one frame to the next and its RANSAC starts from the same seed on every
// call, so a frame gets the same pose in any order: `bench-real --suite` runs each peer once per
// clip and replays these poses in every frame order (GroundTruthBenchmarkOptions::peerPoses),
// and PeerPoseCache keeps them between runs.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/research/sixdof/GroundTruthSequence.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack::app {

struct PeerPoses {
  std::string method;      // its name in tables, e.g. "SIFT+PnP"
  int modelPoints = 0;     // points triangulated from the references
  std::string modelError;  // why the references gave the peer no model ("" when they did)
  // Per frame of the sequence (frames[k]): the world->camera pose, or why there is none, and the
  // thread CPU time locate() took (ms; 0 without a model).
  std::vector<std::optional<RigidPose>> poses;
  std::vector<std::string> reasons;
  std::vector<double> cpuMs;
};

// Called after every `kPeerProgressFrames` frames and after the last: frames done, of `total`.
using PeerProgress = std::function<void(int done, int total)>;
inline constexpr int kPeerProgressFrames = 50;

// `detector`: sift, akaze or orb (PerFramePnpPeer's default parameters); `references`: indices
// into sequence.frames, each with a true pose. References that give the peer no model (fewer
// than 6 triangulated points) leave every frame without a pose, the reason "no model: ...".
// Throws reftrack::Error on another detector name or a reference without a true pose.
PeerPoses computePeerPoses(const std::string& detector, const GroundTruthSequence& sequence,
                           const std::vector<int>& references, const PeerProgress& progress = {});

}  // namespace reftrack::app
