// The order in which the frames of a sequence are solved when tracking restarts at anchors:
// frame 0's init_pose.txt and every keyframe (keyframes.h). Tracking runs forwards and backwards
// from each anchor, and each frame is solved once, from its nearer anchor (on a tie the earlier
// one, tracked forwards): frames before the first anchor are tracked backwards from it, frames
// after the last forwards from it, and a gap between anchors a < b splits at (a + b) / 2.
//
// Why the nearer anchor and not the better of two solves: the energies of two solves of one
// frame are not comparable (each learned its colour models at its own pose), the drift of a
// tracker grows with the frames tracked, and solving each frame once costs what a single
// forward pass costs.
#pragma once

#include <vector>

namespace bcot {

// Frames [first, end) tracked from `anchor`: forwards (first == anchor; the anchor frame is
// the segment's first) or backwards (end == anchor; solved from anchor − 1 down to first, the
// anchor solved first to start the tracker but not recorded by this segment).
struct TrackingSegment {
  int anchor = 0;
  int first = 0;
  int end = 0;
  bool backward = false;
};

// Segments covering [0, num_frames) in frame order. `anchors`: frame indices, sorted, distinct,
// in [0, num_frames) (CHECKed), at least one.
std::vector<TrackingSegment> PlanTracking(const std::vector<int>& anchors, int num_frames);

}  // namespace bcot
