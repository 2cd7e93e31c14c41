// A camera as the recorder sees it: start, (software-)trigger, grab one frame with a
// timeout, stop. Aravis cameras implement it (aravis_frame_source.h); tests use scripted
// in-memory sources, so the recorder logic is tested without a camera.
//
// Timestamps: `host_timestamp_ns` is the host's CLOCK_REALTIME (ns since the Unix epoch) when
// the frame arrived — one clock for all cameras, used to pair frames across cameras.
// `device_timestamp_ns` is the camera's own clock (arbitrary epoch, one per camera), kept for
// precise frame intervals of each camera.
//
// Thread safety: one thread uses a source at a time.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

#include "bcot/core/status.h"

namespace bcot {

struct Frame {
  cv::Mat image;  // CV_8UC1 (mono), CV_8UC3 (BGR) or CV_16UC1 (mono, 10–16 bit)
  int64_t device_timestamp_ns = 0;
  int64_t host_timestamp_ns = 0;
  uint64_t frame_id = 0;  // the camera's counter; need not start at 0
};

enum class GrabStatus {
  kFrame,   // `frame` holds a complete image
  kMissed,  // no complete frame within the timeout (dropped, incomplete or late)
  kLost,    // the camera is gone (unplugged, powered off, control lost): stop recording
};

struct GrabResult {
  GrabStatus status = GrabStatus::kMissed;
  Frame frame;
  std::string message;  // why, for kMissed and kLost
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;

  // Camera name: the folder name in the sequence directory and the rig.yaml camera name.
  virtual const std::string& name() const = 0;
  // Where it comes from, for messages ("Aravis device 'Fake_1'").
  virtual std::string description() const = 0;

  // Starts acquisition. Errors name the camera.
  virtual Status Start() = 0;
  // Requests one frame in software-trigger mode; a no-op returning OK in hardware-trigger and
  // free-running modes. An error means the camera did not accept the command (usually lost).
  virtual Status Trigger() = 0;
  // Waits up to `timeout_ms` for the next frame.
  virtual GrabResult Grab(int timeout_ms) = 0;
  // Stops acquisition; safe to call twice and after a loss.
  virtual void Stop() = 0;
};

}  // namespace bcot
