#include "bcot/annotate/tracking_plan.h"

#include <gtest/gtest.h>

#include <vector>

namespace bcot {
namespace {

// Which anchor each frame is solved from, and whether backwards.
std::vector<int> AnchorOfFrames(const std::vector<TrackingSegment>& segments, int num_frames) {
  std::vector<int> anchor(num_frames, -1);
  int next = 0;
  for (const TrackingSegment& segment : segments) {
    EXPECT_EQ(segment.first, next);  // in frame order, no gap, no overlap
    EXPECT_LT(segment.first, segment.end);
    if (segment.backward) {
      EXPECT_EQ(segment.end, segment.anchor);
    } else {
      EXPECT_EQ(segment.first, segment.anchor);
    }
    for (int f = segment.first; f < segment.end; ++f) anchor[f] = segment.anchor;
    next = segment.end;
  }
  EXPECT_EQ(next, num_frames);
  return anchor;
}

TEST(TrackingPlanTest, FrameZeroOnlyIsOneForwardPass) {
  const std::vector<TrackingSegment> segments = PlanTracking({0}, 5);
  ASSERT_EQ(segments.size(), 1u);
  EXPECT_FALSE(segments[0].backward);
  EXPECT_EQ(segments[0].end, 5);
}

TEST(TrackingPlanTest, AKeyframeTracksBackwardsAndForwards) {
  const std::vector<TrackingSegment> segments = PlanTracking({3}, 6);
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_TRUE(segments[0].backward);
  EXPECT_EQ(AnchorOfFrames(segments, 6), (std::vector<int>{3, 3, 3, 3, 3, 3}));
}

TEST(TrackingPlanTest, EachFrameFromItsNearerAnchorTiesToTheEarlier) {
  EXPECT_EQ(AnchorOfFrames(PlanTracking({0, 4, 9}, 11), 11),
            (std::vector<int>{0, 0, 0, 4, 4, 4, 4, 9, 9, 9, 9}));
  EXPECT_EQ(AnchorOfFrames(PlanTracking({1, 2, 3}, 4), 4), (std::vector<int>{1, 1, 2, 3}));
  EXPECT_EQ(AnchorOfFrames(PlanTracking({5}, 6), 6), (std::vector<int>{5, 5, 5, 5, 5, 5}));
}

}  // namespace
}  // namespace bcot
