#include "app/research/sixdof/FrameOrder.hpp"

#include <algorithm>
#include <charconv>
#include <numeric>
#include <random>
#include <set>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

const char* const kKnownOrders =
    "sequence, shuffled, shuffled-sequence, cuts:N, stride:K, away:N, return:A-B+C-D+...";

// The whole number after "cuts:" / "stride:" / "away:", or -1 when the rest is not one.
int wholeNumber(const char* begin, const char* end) {
  if (begin == end || !std::all_of(begin, end, [](char c) { return c >= '0' && c <= '9'; }))
    return -1;
  int value = 0;
  const auto [last, ec] = std::from_chars(begin, end, value);
  return ec == std::errc() && last == end ? value : -1;
}
int countAfter(const std::string& text, std::size_t prefix) {
  return wholeNumber(text.data() + prefix, text.data() + text.size());
}

// "A-B+C-D+..." after "return:", or an empty list when it is not that.
std::vector<FrameRange> rangesAfter(const std::string& text, std::size_t prefix) {
  std::vector<FrameRange> ranges;
  std::size_t at = prefix;
  while (at <= text.size()) {
    const std::size_t plus = std::min(text.find('+', at), text.size());
    const std::size_t dash = text.find('-', at);
    if (dash == std::string::npos || dash >= plus) return {};
    const int a = wholeNumber(text.data() + at, text.data() + dash);
    const int b = wholeNumber(text.data() + dash + 1, text.data() + plus);
    if (a < 0 || b < 0) return {};
    ranges.push_back({a, b});
    at = plus + 1;
  }
  return ranges;
}

}  // namespace

const std::vector<std::string>& defaultFrameOrders() {
  static const std::vector<std::string> orders = {"sequence", "shuffled"};
  return orders;
}

FrameOrder parseFrameOrder(const std::string& text) {
  if (text == "sequence") return {text, FrameOrderKind::Sequence, 0, {}};
  if (text == "shuffled") return {text, FrameOrderKind::Shuffled, 0, {}};
  if (text == "shuffled-sequence") return {text, FrameOrderKind::ShuffledSequence, 0, {}};
  const std::string bad = "bench-real: --order: '" + text + "': ";
  if (text.rfind("cuts:", 0) == 0) {
    const int n = countAfter(text, 5);
    if (n < 2) throw Error(bad + "N (the segments) must be a whole number >= 2");
    return {"cuts:" + std::to_string(n), FrameOrderKind::Cuts, n, {}};
  }
  if (text.rfind("stride:", 0) == 0) {
    const int k = countAfter(text, 7);
    if (k < 1) throw Error(bad + "K (the stride) must be a whole number >= 1");
    return {"stride:" + std::to_string(k), FrameOrderKind::Stride, k, {}};
  }
  if (text.rfind("away:", 0) == 0) {
    const int n = countAfter(text, 5);
    if (n < 1) throw Error(bad + "N (the frames of the other scene) must be a whole number >= 1");
    return {"away:" + std::to_string(n), FrameOrderKind::Away, n, {}};
  }
  if (text.rfind("return:", 0) == 0) {
    const std::vector<FrameRange> ranges = rangesAfter(text, 7);
    if (ranges.size() < 2)
      throw Error(bad +
                  "needs two or more ranges of frames A-B joined by '+' (the start, ..., the "
                  "return), e.g. return:0-70+110-150+70-0");
    std::string name = "return:";
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      if (i > 0) name += '+';
      name += std::to_string(ranges[i].first);
      name += '-';
      name += std::to_string(ranges[i].last);
    }
    return {name, FrameOrderKind::Return, static_cast<int>(ranges.size()), ranges};
  }
  throw Error("bench-real: --order: unknown order '" + text + "' (known: " + kKnownOrders + ")");
}

std::vector<FrameOrder> parseFrameOrders(const std::vector<std::string>& texts) {
  if (texts.empty()) throw Error("bench-real: --order names no order");
  std::vector<FrameOrder> orders;
  std::set<std::string> named;
  for (const std::string& text : texts) {
    orders.push_back(parseFrameOrder(text));
    if (!named.insert(orders.back().name).second)
      throw Error("bench-real: --order: '" + orders.back().name + "' given twice");
  }
  return orders;
}

FramePlan planFrames(const FrameOrder& order, int frames, std::uint64_t seed) {
  FramePlan plan;
  plan.coldStarts = order.coldStarts();
  std::vector<int> sequence(static_cast<std::size_t>(std::max(frames, 0)));
  std::iota(sequence.begin(), sequence.end(), 0);
  std::mt19937_64 rng(seed);
  switch (order.kind) {
    case FrameOrderKind::Sequence:
      plan.frames = sequence;
      break;
    case FrameOrderKind::Shuffled:
    case FrameOrderKind::ShuffledSequence:
      plan.frames = sequence;
      std::shuffle(plan.frames.begin(), plan.frames.end(), rng);
      break;
    case FrameOrderKind::Cuts: {
      const int n = order.count;
      if (n > frames)
        throw Error("bench-real: --order: '" + order.name + "': " + std::to_string(n) +
                    " segments but only " + std::to_string(frames) + " frames are benchmarked");
      std::vector<int> segments(static_cast<std::size_t>(n));
      std::iota(segments.begin(), segments.end(), 0);
      // Reshuffled until no segment is followed by its successor in time (for n >= 2 about a
      // third of the permutations qualify, half of them for n = 2).
      auto continues = [&] {
        for (std::size_t i = 0; i + 1 < segments.size(); ++i)
          if (segments[i + 1] == segments[i] + 1) return true;
        return false;
      };
      do {
        std::shuffle(segments.begin(), segments.end(), rng);
      } while (continues());
      auto start = [&](int segment) {
        return static_cast<int>(static_cast<long long>(segment) * frames / n);
      };
      for (int segment : segments) {
        if (!plan.frames.empty()) plan.cuts.push_back(plan.frames.size());
        for (int k = start(segment); k < start(segment + 1); ++k) plan.frames.push_back(k);
      }
      break;
    }
    case FrameOrderKind::Stride:
      if (order.count > frames)
        throw Error("bench-real: --order: '" + order.name + "': a stride of " +
                    std::to_string(order.count) + " but only " + std::to_string(frames) +
                    " frames are benchmarked");
      for (int k = 0; k < frames; k += order.count) plan.frames.push_back(k);
      break;
    case FrameOrderKind::Away:
      if (frames < 2)
        throw Error("bench-real: --order: '" + order.name + "' needs at least 2 frames, " +
                    std::to_string(frames) + " are benchmarked");
      plan.frames.assign(sequence.begin(), sequence.begin() + frames / 2);
      plan.awayStart = plan.frames.size();
      for (int j = 0; j < order.count; ++j) plan.frames.push_back(-1 - j);
      plan.awayEnd = plan.frames.size();
      plan.frames.insert(plan.frames.end(), sequence.begin() + frames / 2, sequence.end());
      break;
    case FrameOrderKind::Return: {
      std::set<int> seen;
      for (const FrameRange& r : order.ranges) {
        if (std::max(r.first, r.last) >= frames)
          throw Error("bench-real: --order: '" + order.name + "': the range " +
                      std::to_string(r.first) + "-" + std::to_string(r.last) +
                      " reaches beyond the " + std::to_string(frames) +
                      " frames benchmarked (0 .. " + std::to_string(frames - 1) + ")");
        plan.rangeStarts.push_back(plan.frames.size());
        const int step = r.last >= r.first ? 1 : -1;
        for (int k = r.first;; k += step) {
          plan.frames.push_back(k);
          plan.repeatsFrames = plan.repeatsFrames || !seen.insert(k).second;
          if (k == r.last) break;
        }
      }
      plan.awayStart = plan.rangeStarts[1];
      plan.awayEnd = plan.rangeStarts.back();
      break;
    }
  }
  return plan;
}

std::vector<bool> playedFrames(const FramePlan& plan, int frames) {
  std::vector<bool> played(static_cast<std::size_t>(std::max(frames, 0)), false);
  for (int k : plan.frames)
    if (k >= 0 && k < frames) played[static_cast<std::size_t>(k)] = true;
  return played;
}

}  // namespace reftrack::app
