// Groups frames of N cameras into synchronized frame sets by host timestamp.
//
// A frame set is one frame per camera whose host timestamps lie within `max_skew_ns` of each
// other. Frames are added per camera in arrival order. A frame that can no longer be part of
// any set — it is older than another camera's oldest pending frame by more than the
// tolerance, i.e. its partner was dropped — is discarded and counted, so one lost frame costs
// one frame set, never the synchronization of the rest.
//
// Not thread-safe.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "bcot/capture/frame_source.h"

namespace bcot {

class FrameSetMatcher {
 public:
  // `max_pending` bounds each camera's queue (oldest frames are discarded first) while
  // another camera delivers nothing.
  FrameSetMatcher(int num_cameras, int64_t max_skew_ns, int max_pending = 16);

  void Add(int camera, Frame frame);

  // The oldest complete frame set (frames in camera order), or nothing yet.
  std::optional<std::vector<Frame>> PopSet();

  int num_cameras() const { return static_cast<int>(pending_.size()); }
  int64_t discarded(int camera) const { return discarded_.at(camera); }
  int pending(int camera) const { return static_cast<int>(pending_.at(camera).size()); }

 private:
  std::vector<std::deque<Frame>> pending_;
  std::vector<int64_t> discarded_;
  int64_t max_skew_ns_;
  int max_pending_;
};

}  // namespace bcot
