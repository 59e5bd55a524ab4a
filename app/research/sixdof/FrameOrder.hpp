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
  Away,    // "away:N": in order, with N frames of another scene played after the first half
  Return,  // "return:A-B+C-D+...": ranges of the clip's own frames as one sequence (a start, a
           // stretch away from the mapped scene, the return), frames may repeat
};

// One range of a return order: frames first .. last, inclusive, backwards when last < first.
struct FrameRange {
  int first = 0, last = 0;
  int size() const { return (last >= first ? last - first : first - last) + 1; }
  bool operator==(const FrameRange&) const = default;
};

struct FrameOrder {
  std::string name;  // as the table, CSV and progress lines name it, e.g. "cuts:8"
  FrameOrderKind kind = FrameOrderKind::Sequence;
  int count = 0;  // cuts:N: N; stride:K: K; away:N: N; return: the ranges; 0 for the others
  std::vector<FrameRange> ranges;  // return: the ranges, in the order played
  bool coldStarts() const { return kind == FrameOrderKind::Shuffled; }
};

// The default `--order` list: today's two orders.
const std::vector<std::string>& defaultFrameOrders();  // sequence, shuffled

// One `--order` name: "sequence", "shuffled", "shuffled-sequence", "cuts:N" (N >= 2),
// "stride:K" (K >= 1), "away:N" (N >= 1) or "return:A-B+C-D+..." (at least two ranges of frame
// indices >= 0, each inclusive and played backwards when B < A). Throws reftrack::Error naming
// --order and the bad name otherwise.
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
  // first frame of the sequence after it); return: of the first frame after the first range and
  // of the first frame of the last range (the return); both 0 for the other orders.
  std::size_t awayStart = 0, awayEnd = 0;
  // return: the position in `frames` where each range starts (one per range).
  std::vector<std::size_t> rangeStarts;
  // A frame may be played more than once (return orders): score per position, not per frame.
  bool repeatsFrames = false;
};

// The plan of `order` over frames 0 .. frames-1, its shuffles seeded by `seed`. `shuffled` and
// `shuffled-sequence` play the same permutation; cuts:N plays the segments [i F / N, (i+1) F / N)
// in a shuffled order where no segment directly follows the one before it in time (so every cut is
// a jump); away:N plays frames [0, F / 2), N frames of the other scene, then [F / 2, F); return
// plays its ranges one after the other. Throws reftrack::Error naming --order when N or K exceeds
// `frames` (away:N: when F < 2; return: a range reaching frame F or beyond).
FramePlan planFrames(const FrameOrder& order, int frames, std::uint64_t seed);

// Per frame index (0 .. frames-1): whether `plan` plays it.
std::vector<bool> playedFrames(const FramePlan& plan, int frames);

}  // namespace reftrack::app
