#include "app/research/sixdof/FrameOrder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <set>

#include "ErrorMessage.hpp"

namespace reftrack::app {
namespace {

TEST(FrameOrder, ParsesEveryOrderByName) {
  struct Case {
    const char* text;
    const char* name;
    FrameOrderKind kind;
    int count;
    bool coldStarts;
  };
  for (const Case& c :
       {Case{"sequence", "sequence", FrameOrderKind::Sequence, 0, false},
        Case{"shuffled", "shuffled", FrameOrderKind::Shuffled, 0, true},
        Case{"shuffled-sequence", "shuffled-sequence", FrameOrderKind::ShuffledSequence, 0, false},
        Case{"cuts:8", "cuts:8", FrameOrderKind::Cuts, 8, false},
        Case{"cuts:2", "cuts:2", FrameOrderKind::Cuts, 2, false},
        Case{"cuts:012", "cuts:12", FrameOrderKind::Cuts, 12, false},
        Case{"stride:1", "stride:1", FrameOrderKind::Stride, 1, false},
        Case{"stride:4", "stride:4", FrameOrderKind::Stride, 4, false},
        Case{"away:900", "away:900", FrameOrderKind::Away, 900, false}}) {
    const FrameOrder o = parseFrameOrder(c.text);
    EXPECT_EQ(o.name, c.name) << c.text;
    EXPECT_EQ(o.kind, c.kind) << c.text;
    EXPECT_EQ(o.count, c.count) << c.text;
    EXPECT_EQ(o.coldStarts(), c.coldStarts) << c.text;
  }
  const std::vector<FrameOrder> defaults = parseFrameOrders(defaultFrameOrders());
  ASSERT_EQ(defaults.size(), 2u);
  EXPECT_EQ(defaults[0].kind, FrameOrderKind::Sequence);
  EXPECT_EQ(defaults[1].kind, FrameOrderKind::Shuffled);
}

TEST(FrameOrder, BadNamesAreErrorsNamingTheOrderOption) {
  auto message = [](const std::string& text) {
    return test::errorMessage([&] { parseFrameOrder(text); });
  };
  for (const char* unknown : {"zigzag", "Sequence", "shuffled:3", "cuts", "stride", ""}) {
    const std::string m = message(unknown);
    EXPECT_NE(m.find("bench-real: --order: unknown order '" + std::string(unknown) + "'"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("known: sequence, shuffled, shuffled-sequence, cuts:N, stride:K, away:N"),
              std::string::npos)
        << m;
  }
  for (const char* badCuts :
       {"cuts:1", "cuts:0", "cuts:", "cuts:-3", "cuts:4x", "cuts:2.5", "cuts:99999999999999"}) {
    const std::string m = message(badCuts);
    EXPECT_NE(m.find("--order: '" + std::string(badCuts) +
                     "': N (the segments) must be a whole "
                     "number >= 2"),
              std::string::npos)
        << m;
  }
  for (const char* badStride : {"stride:0", "stride:", "stride:-1", "stride:k"}) {
    const std::string m = message(badStride);
    EXPECT_NE(m.find("--order: '" + std::string(badStride) +
                     "': K (the stride) must be a whole "
                     "number >= 1"),
              std::string::npos)
        << m;
  }
  auto listMessage = [](const std::vector<std::string>& texts) {
    return test::errorMessage([&] { parseFrameOrders(texts); });
  };
  EXPECT_NE(listMessage({}).find("--order names no order"), std::string::npos);
  EXPECT_NE(listMessage({"sequence", "cuts:4", "cuts:04"}).find("--order: 'cuts:4' given twice"),
            std::string::npos);
  EXPECT_NE(listMessage({"sequence", "wobble"}).find("unknown order 'wobble'"), std::string::npos);
  EXPECT_EQ(listMessage({"sequence", "shuffled-sequence", "cuts:8", "stride:4"}), "(no error)");
}

// cuts:N: N contiguous segments of about equal length (sizes differ by at most one), played one
// after another so that every frame is played exactly once; N-1 cuts, each at a segment's start
// and each a jump (the frame after a cut is not the one after the frame before it).
TEST(FrameOrder, CutsPlayNSegmentsCoveringEveryFrameOnce) {
  for (int frames : {2, 7, 40, 401})
    for (int n : {2, 3, 8, 13})
      for (std::uint64_t seed : {1u, 2u, 99u}) {
        if (n > frames) continue;
        const FramePlan plan =
            planFrames(parseFrameOrder("cuts:" + std::to_string(n)), frames, seed);
        const std::string what = std::to_string(frames) + " frames, cuts:" + std::to_string(n) +
                                 ", seed " + std::to_string(seed);
        EXPECT_FALSE(plan.coldStarts) << what;
        ASSERT_EQ(plan.frames.size(), static_cast<std::size_t>(frames)) << what;
        std::vector<int> sorted = plan.frames;
        std::sort(sorted.begin(), sorted.end());
        std::vector<int> every(static_cast<std::size_t>(frames));
        std::iota(every.begin(), every.end(), 0);
        EXPECT_EQ(sorted, every) << what;  // each frame exactly once
        ASSERT_EQ(plan.cuts.size(), static_cast<std::size_t>(n - 1)) << what;
        // The segments between cuts: contiguous runs of frames, about equal in length.
        std::vector<std::size_t> starts = {0};
        starts.insert(starts.end(), plan.cuts.begin(), plan.cuts.end());
        starts.push_back(plan.frames.size());
        std::set<int> segmentStarts;
        int shortest = frames, longest = 0;
        for (std::size_t s = 0; s + 1 < starts.size(); ++s) {
          ASSERT_LT(starts[s], starts[s + 1]) << what;
          for (std::size_t i = starts[s] + 1; i < starts[s + 1]; ++i)
            EXPECT_EQ(plan.frames[i], plan.frames[i - 1] + 1) << what << " at " << i;
          const int length = static_cast<int>(starts[s + 1] - starts[s]);
          shortest = std::min(shortest, length);
          longest = std::max(longest, length);
          segmentStarts.insert(plan.frames[starts[s]]);
          if (s > 0) {
            EXPECT_NE(plan.frames[starts[s]], plan.frames[starts[s] - 1] + 1)
                << what << " cut " << s;
          }
        }
        EXPECT_EQ(segmentStarts.size(), static_cast<std::size_t>(n)) << what;
        EXPECT_LE(longest - shortest, 1) << what;
        // The same seed, the same plan.
        EXPECT_EQ(planFrames(parseFrameOrder("cuts:" + std::to_string(n)), frames, seed).frames,
                  plan.frames)
            << what;
      }
  // A different seed shuffles the segments differently (for some seed).
  const FramePlan one = planFrames(parseFrameOrder("cuts:8"), 400, 1);
  bool differs = false;
  for (std::uint64_t seed = 2; seed < 6; ++seed)
    differs = differs || planFrames(parseFrameOrder("cuts:8"), 400, seed).frames != one.frames;
  EXPECT_TRUE(differs);
}

TEST(FrameOrder, StrideAndTheShuffledOrders) {
  const FramePlan stride = planFrames(parseFrameOrder("stride:4"), 18, 1);
  EXPECT_EQ(stride.frames, (std::vector<int>{0, 4, 8, 12, 16}));
  EXPECT_TRUE(stride.cuts.empty());
  EXPECT_FALSE(stride.coldStarts);
  const std::vector<bool> played = playedFrames(stride, 18);
  for (int k = 0; k < 18; ++k) EXPECT_EQ(played[static_cast<std::size_t>(k)], k % 4 == 0) << k;
  EXPECT_EQ(planFrames(parseFrameOrder("stride:18"), 18, 1).frames, std::vector<int>{0});
  std::vector<int> every(30);
  std::iota(every.begin(), every.end(), 0);
  EXPECT_EQ(planFrames(parseFrameOrder("sequence"), 30, 5).frames, every);
  EXPECT_EQ(planFrames(parseFrameOrder("stride:1"), 30, 5).frames, every);
  // shuffled and shuffled-sequence: the same permutation of every frame; only the first resets.
  const FramePlan cold = planFrames(parseFrameOrder("shuffled"), 30, 5);
  const FramePlan warm = planFrames(parseFrameOrder("shuffled-sequence"), 30, 5);
  EXPECT_TRUE(cold.coldStarts);
  EXPECT_FALSE(warm.coldStarts);
  EXPECT_EQ(cold.frames, warm.frames);
  EXPECT_NE(cold.frames, every);
  std::vector<int> sorted = warm.frames;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, every);
  EXPECT_NE(planFrames(parseFrameOrder("shuffled"), 30, 6).frames, cold.frames);
}

TEST(FrameOrder, MoreSegmentsOrAStrideBeyondTheFramesIsAnError) {
  std::string m = test::errorMessage([] { planFrames(parseFrameOrder("cuts:9"), 8, 1); });
  EXPECT_NE(m.find("bench-real: --order: 'cuts:9': 9 segments but only 8 frames are benchmarked"),
            std::string::npos)
      << m;
  m = test::errorMessage([] { planFrames(parseFrameOrder("stride:9"), 8, 1); });
  EXPECT_NE(
      m.find("bench-real: --order: 'stride:9': a stride of 9 but only 8 frames are benchmarked"),
      std::string::npos)
      << m;
  EXPECT_EQ(test::errorMessage([] { planFrames(parseFrameOrder("cuts:8"), 8, 1); }), "(no error)");
}

// away:N plays the first half in order, N frames of the other scene (-1 - j), then the rest.
TEST(FrameOrder, AwayPlaysTheOtherSceneBetweenTheTwoHalves) {
  const FramePlan plan = planFrames(parseFrameOrder("away:3"), 7, 1);
  EXPECT_EQ(plan.frames, (std::vector<int>{0, 1, 2, -1, -2, -3, 3, 4, 5, 6}));
  EXPECT_EQ(plan.awayStart, 3u);
  EXPECT_EQ(plan.awayEnd, 6u);
  EXPECT_FALSE(plan.coldStarts);
  EXPECT_TRUE(plan.cuts.empty());
  const std::vector<bool> played = playedFrames(plan, 7);
  EXPECT_EQ(std::count(played.begin(), played.end(), true), 7);
  EXPECT_EQ(planFrames(parseFrameOrder("sequence"), 7, 1).awayEnd, 0u);
  EXPECT_THROW(parseFrameOrder("away:0"), Error);
  EXPECT_THROW(planFrames(parseFrameOrder("away:5"), 1, 1), Error);
}

// return:A-B+C-D+...: the ranges one after the other (backwards when B < A), frames may repeat;
// awayStart/awayEnd bound what lies between the first range and the last (the return).
TEST(FrameOrder, ReturnPlaysItsRangesAsOneSequence) {
  const FrameOrder o = parseFrameOrder("return:0-3+8-9+03-1");
  EXPECT_EQ(o.name, "return:0-3+8-9+3-1");
  EXPECT_EQ(o.kind, FrameOrderKind::Return);
  EXPECT_EQ(o.count, 3);
  EXPECT_FALSE(o.coldStarts());
  ASSERT_EQ(o.ranges.size(), 3u);
  EXPECT_EQ(o.ranges[2], (FrameRange{3, 1}));
  EXPECT_EQ(o.ranges[2].size(), 3);
  const FramePlan plan = planFrames(o, 10, 1);
  EXPECT_EQ(plan.frames, (std::vector<int>{0, 1, 2, 3, 8, 9, 3, 2, 1}));
  EXPECT_EQ(plan.rangeStarts, (std::vector<std::size_t>{0, 4, 6}));
  EXPECT_EQ(plan.awayStart, 4u);
  EXPECT_EQ(plan.awayEnd, 6u);
  EXPECT_TRUE(plan.repeatsFrames);
  EXPECT_FALSE(plan.coldStarts);
  EXPECT_TRUE(plan.cuts.empty());
  const std::vector<bool> played = playedFrames(plan, 10);
  EXPECT_EQ(std::count(played.begin(), played.end(), true), 6);  // 0 1 2 3 8 9
  // Ranges that do not repeat a frame; a one-frame range.
  const FramePlan once = planFrames(parseFrameOrder("return:0-1+5-5+2-3"), 6, 1);
  EXPECT_EQ(once.frames, (std::vector<int>{0, 1, 5, 2, 3}));
  EXPECT_FALSE(once.repeatsFrames);
  EXPECT_EQ(parseFrameOrders({"sequence", "return:0-1+1-0"}).size(), 2u);
}

TEST(FrameOrder, BadReturnOrdersAreErrors) {
  for (const char* bad :
       {"return:", "return:0-70", "return:0-70+", "return:0-70+x-3", "return:0-70+5", "return:0+70",
        "return:-1-3+4-5", "return:0-70++3-4", "return:1-2-3+4-5"}) {
    const std::string m = test::errorMessage([&] { parseFrameOrder(bad); });
    EXPECT_NE(m.find("--order: '" + std::string(bad) + "': needs two or more ranges of frames A-B"),
              std::string::npos)
        << bad << ": " << m;
  }
  const std::string m =
      test::errorMessage([] { planFrames(parseFrameOrder("return:0-5+9-10+5-0"), 10, 1); });
  EXPECT_NE(m.find("'return:0-5+9-10+5-0': the range 9-10 reaches beyond the 10 frames "
                   "benchmarked (0 .. 9)"),
            std::string::npos)
      << m;
}

}  // namespace
}  // namespace reftrack::app
