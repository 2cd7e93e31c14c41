#include "bcot/capture/frame_set_matcher.h"

#include <gtest/gtest.h>

#include "capture_test_util.h"

namespace bcot {
namespace {

constexpr int64_t kMs = 1000000;

Frame At(int64_t host_ns) { return test::ScriptedFrame(0, 0, host_ns).frame; }

TEST(FrameSetMatcherTest, PairsFramesWithinTheSkew) {
  FrameSetMatcher matcher(2, 5 * kMs);
  matcher.Add(0, At(100 * kMs));
  EXPECT_FALSE(matcher.PopSet().has_value());  // camera 1 has nothing yet
  matcher.Add(1, At(103 * kMs));
  const auto set = matcher.PopSet();
  ASSERT_TRUE(set.has_value());
  ASSERT_EQ(set->size(), 2u);
  EXPECT_EQ((*set)[0].host_timestamp_ns, 100 * kMs);
  EXPECT_EQ((*set)[1].host_timestamp_ns, 103 * kMs);
  EXPECT_FALSE(matcher.PopSet().has_value());
  EXPECT_EQ(matcher.discarded(0) + matcher.discarded(1), 0);
}

TEST(FrameSetMatcherTest, DiscardsAFrameWhosePartnerWasDroppedAndStaysInSync) {
  // Camera 1 lost its frame at t = 140 ms; its next frame (180) pairs with camera 0's 180.
  FrameSetMatcher matcher(2, 5 * kMs);
  for (int64_t t : {100, 140, 180, 220}) matcher.Add(0, At(t * kMs));
  for (int64_t t : {101, 181, 221}) matcher.Add(1, At(t * kMs));
  std::vector<std::pair<int64_t, int64_t>> sets;
  while (auto set = matcher.PopSet()) {
    sets.emplace_back((*set)[0].host_timestamp_ns / kMs, (*set)[1].host_timestamp_ns / kMs);
  }
  const std::vector<std::pair<int64_t, int64_t>> expected = {{100, 101}, {180, 181}, {220, 221}};
  EXPECT_EQ(sets, expected);
  EXPECT_EQ(matcher.discarded(0), 1);
  EXPECT_EQ(matcher.discarded(1), 0);
}

TEST(FrameSetMatcherTest, SkewIsInclusiveAndNothingBeyondItPairs) {
  FrameSetMatcher matcher(3, 5 * kMs);
  matcher.Add(0, At(10 * kMs));
  matcher.Add(1, At(15 * kMs));  // exactly the tolerance
  matcher.Add(2, At(12 * kMs));
  EXPECT_TRUE(matcher.PopSet().has_value());
  matcher.Add(0, At(50 * kMs));
  matcher.Add(1, At(56 * kMs));  // 6 ms after camera 0: its frame is stale
  matcher.Add(2, At(55 * kMs));
  EXPECT_FALSE(matcher.PopSet().has_value());
  EXPECT_EQ(matcher.discarded(0), 1);
  EXPECT_EQ(matcher.pending(1), 1);
  EXPECT_EQ(matcher.pending(2), 1);
}

TEST(FrameSetMatcherTest, BoundsTheQueueOfACameraWhosePartnerIsSilent) {
  FrameSetMatcher matcher(2, kMs, /*max_pending=*/4);
  for (int i = 0; i < 10; ++i) matcher.Add(0, At(i * 10 * kMs));
  EXPECT_EQ(matcher.pending(0), 4);
  EXPECT_EQ(matcher.discarded(0), 6);
  EXPECT_FALSE(matcher.PopSet().has_value());
}

}  // namespace
}  // namespace bcot
