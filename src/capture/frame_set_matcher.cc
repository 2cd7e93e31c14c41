#include "bcot/capture/frame_set_matcher.h"

#include <algorithm>

namespace bcot {

FrameSetMatcher::FrameSetMatcher(int num_cameras, int64_t max_skew_ns, int max_pending)
    : pending_(num_cameras),
      discarded_(num_cameras, 0),
      max_skew_ns_(max_skew_ns),
      max_pending_(max_pending) {
  BCOT_CHECK(num_cameras >= 1);
  BCOT_CHECK(max_skew_ns >= 0);
  BCOT_CHECK(max_pending >= 1);
}

void FrameSetMatcher::Add(int camera, Frame frame) {
  std::deque<Frame>& queue = pending_.at(camera);
  queue.push_back(std::move(frame));
  while (static_cast<int>(queue.size()) > max_pending_) {
    queue.pop_front();
    ++discarded_[camera];
  }
}

std::optional<std::vector<Frame>> FrameSetMatcher::PopSet() {
  while (true) {
    int64_t newest = 0;
    for (const std::deque<Frame>& queue : pending_) {
      if (queue.empty()) return std::nullopt;
      newest = std::max(newest, queue.front().host_timestamp_ns);
    }
    // Heads older than the newest head by more than the tolerance lost their partners.
    bool discarded_any = false;
    for (size_t c = 0; c < pending_.size(); ++c) {
      std::deque<Frame>& queue = pending_[c];
      while (!queue.empty() && queue.front().host_timestamp_ns < newest - max_skew_ns_) {
        queue.pop_front();
        ++discarded_[c];
        discarded_any = true;
      }
    }
    if (discarded_any) continue;  // some queue may be empty now, or a newer head appeared
    std::vector<Frame> set;
    set.reserve(pending_.size());
    for (std::deque<Frame>& queue : pending_) {
      set.push_back(std::move(queue.front()));
      queue.pop_front();
    }
    return set;
  }
}

}  // namespace bcot
