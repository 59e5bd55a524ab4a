#include "app/research/sixdof/PerFramePeerPoses.hpp"

#include <memory>

#include "app/research/baselines/PerFramePnpPeer.hpp"
#include "engine/core/Error.hpp"
#include "engine/core/ThreadCpuClock.hpp"

namespace reftrack::app {

PeerPoses computePeerPoses(const std::string& detector, const GroundTruthSequence& s,
                           const std::vector<int>& references, const PeerProgress& progress) {
  std::vector<cv::Mat> images;
  std::vector<RigidPose> poses;
  for (int r : references) {
    const std::size_t k = static_cast<std::size_t>(r);
    if (r < 0 || k >= s.frames.size() || !s.truth[k])
      throw Error("per-frame peer: reference frame " + std::to_string(s.firstFrame + r) +
                  " is not a frame of the sequence with a true pose");
    images.push_back(s.frames[k]);
    poses.push_back(*s.truth[k]);
  }
  PeerPoses out;
  out.method = perFramePnpPeerName(detector);
  const int total = static_cast<int>(s.frames.size());
  out.poses.resize(s.frames.size());
  out.reasons.resize(s.frames.size());
  out.cpuMs.assign(s.frames.size(), 0.0);
  std::unique_ptr<PerFramePnpPeer> peer;
  try {
    peer = std::make_unique<PerFramePnpPeer>(detector, s.camera, images, poses);
  } catch (const Error& e) {
    if (detector != "sift" && detector != "akaze" && detector != "orb") throw;
    out.modelError = e.what();
    out.reasons.assign(s.frames.size(), "no model: " + out.modelError);
    if (progress) progress(total, total);
    return out;
  }
  out.modelPoints = peer->modelPoints();
  for (int k = 0; k < total; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    const double cpu0 = threadCpuMs();
    const PerFramePnpResult r = peer->locate(s.frames[i]);
    out.cpuMs[i] = threadCpuMs() - cpu0;
    out.poses[i] = r.worldToCamera;
    if (!r.worldToCamera) out.reasons[i] = peer->noPoseReason(r);
    if (progress && ((k + 1) % kPeerProgressFrames == 0 || k + 1 == total)) progress(k + 1, total);
  }
  return out;
}

}  // namespace reftrack::app
