// The order in which the frames of a sequence are solved when tracking restarts at anchors:
// frame 0's init_pose.txt and every keyframe (keyframes.h). Tracking runs forwards and backwards
// from each anchor, and each frame belongs to its nearer anchor (on a tie the earlier one,
// tracked forwards): frames before the first anchor are tracked backwards from it, frames after
// the last forwards from it, and a gap between anchors a < b splits at (a + b) / 2.
//
// In a gap the annotator (annotator.cc) also solves every frame from the other anchor and keeps
// that solve instead when the two disagree and it scores better with PoseScorer
// (pose_scorer.h): a keyframe set just after a jump that lost tracking would otherwise hand the
// frames before it, down to the middle of the gap, to a backward track across the same jump.
// The trackers' own energies cannot make that choice (each learned its colour models at its
// own poses); PoseScorer learns them at the pose it scores. Frames outside gaps, and frames
// whose two solves agree, keep the nearer anchor's solve: a tracker's drift grows with the
// frames tracked.
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
