// bcot's own region-based tracker behind the MonocularTracker interface, so `bcot eval
// --online` can score it with the BCOT/RBOT protocol: a MultiViewTracker with one view (the
// joint solver of DESIGN.md with a single camera is monocular tracking, paper §4.7).
//
// Poses cross the interface as cam_from_object (O_t, mm); inside, the tracker works on
// cam_from_objcentre (O_o, the mesh's bounding-box centre; see se3_manifold.h).
//   Reset(image, T):  colour models learned from scratch at T (no solve), as after a protocol
//                     reset at ground truth.
//   Track(image):     one MultiViewTracker::Track from the last estimate. A solve that is not
//                     usable (object out of view, solver failure) is an error status, which the
//                     protocol counts as a lost frame.
#pragma once

#include <memory>

#include "bcot/eval/monocular_tracker.h"
#include "bcot/optim/multi_view_tracker.h"

namespace bcot {

// A factory building one RegionMonocularTracker per sequence with `options` (e.g. the
// `tracker` part of configs/track.yaml). Errors: invalid options or camera (kInvalidConfig).
MonocularTrackerFactory MakeRegionTrackerFactory(const MultiViewTrackerOptions& options);

}  // namespace bcot
