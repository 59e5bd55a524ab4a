#pragma once
// The frame orders of `bench-real --input --order`: which frames a method is given, in which
// order, and whether it is reset (a cold start) before each. Every order but `shuffled` plays its
// frames as one sequence, so a tracker carries its state across abrupt changes of view.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace reftrack::app {

enum class FrameOrderKind {
  Sequence,          // "sequence": every frame in order
  Shuffled,          // "shuffled": every frame in a shuffled order, each a cold start
  ShuffledSequence,  // "shuffled-sequence": that shuffled order played as one sequence, no reset
  Cuts,              // "cuts:N": N contiguous segments in a shuffled order, one sequence (N-1 cuts)
  Stride,            // "stride:K": frames 0, K, 2K, ... in order, one sequence (fast motion)
  Away,  // "away:N": in order, with N frames of another scene played after the first half
};

struct FrameOrder {
  std::string name;  // as the table, CSV and progress lines name it, e.g. "cuts:8"
  FrameOrderKind kind = FrameOrderKind::Sequence;
  int count = 0;  // cuts:N: N; stride:K: K; away:N: N; 0 for the others
  bool coldStarts() const { return kind == FrameOrderKind::Shuffled; }
};

// The default `--order` list: today's two orders.
const std::vector<std::string>& defaultFrameOrders();  // sequence, shuffled

// One `--order` name: "sequence", "shuffled", "shuffled-sequence", "cuts:N" (N >= 2),
// "stride:K" (K >= 1) or "away:N" (N >= 1). Throws reftrack::Error naming --order and the bad name
// otherwise.
FrameOrder parseFrameOrder(const std::string& text);
// A whole `--order` list: at least one name, none given twice (as parseFrameOrder throws).
std::vector<FrameOrder> parseFrameOrders(const std::vector<std::string>& texts);

// What one order plays of a sequence's first `frames` frames.
struct FramePlan {
  // Frame indices in the order played; away:N: -1 - j for the j-th frame of the other scene.
  std::vector<int> frames;
  std::vector<std::size_t> cuts;  // cuts:N: positions in `frames` starting a segment (N-1 of them)
  bool coldStarts = false;        // a cold start before every frame
  // away:N: positions in `frames` of the first frame of the other scene and of the return (the
  // first frame of the sequence after it); both 0 for the other orders.
  std::size_t awayStart = 0, awayEnd = 0;
};

// The plan of `order` over frames 0 .. frames-1, its shuffles seeded by `seed`. `shuffled` and
// `shuffled-sequence` play the same permutation; cuts:N plays the segments [i F / N, (i+1) F / N)
// in a shuffled order where no segment directly follows the one before it in time (so every cut is
// a jump); away:N plays frames [0, F / 2), N frames of the other scene, then [F / 2, F). Throws
// reftrack::Error naming --order when N or K exceeds `frames` (away:N: when F < 2).
FramePlan planFrames(const FrameOrder& order, int frames, std::uint64_t seed);

// Per frame index (0 .. frames-1): whether `plan` plays it.
std::vector<bool> playedFrames(const FramePlan& plan, int frames);

}  // namespace reftrack::app
