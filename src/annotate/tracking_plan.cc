#include "bcot/annotate/tracking_plan.h"

#include "bcot/core/status.h"

namespace bcot {

std::vector<TrackingSegment> PlanTracking(const std::vector<int>& anchors, int num_frames) {
  BCOT_CHECK(!anchors.empty());
  std::vector<TrackingSegment> segments;
  int next = 0;  // first frame no segment covers yet
  for (size_t i = 0; i < anchors.size(); ++i) {
    const int anchor = anchors[i];
    BCOT_CHECK(anchor >= next && anchor < num_frames);
    if (next < anchor) segments.push_back({anchor, next, anchor, /*backward=*/true});
    // A frame f between a and b belongs to a while f − a <= b − f.
    const int end = i + 1 < anchors.size() ? (anchor + anchors[i + 1]) / 2 + 1 : num_frames;
    segments.push_back({anchor, anchor, end, /*backward=*/false});
    next = end;
  }
  return segments;
}

}  // namespace bcot
