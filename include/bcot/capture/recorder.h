// Records synchronized frame sets from N frame sources into a sequence directory.
//
// Loop: trigger every source (a no-op unless software-triggered), grab one frame from each,
// pair frames across cameras by host timestamp (FrameSetMatcher), commit each complete set
// (SequenceWriter) — so the directory is valid after every set. Stops, leaving a valid
// directory, when: max_frame_sets or max_duration_s is reached, RequestStop() was called (e.g.
// from a SIGINT handler), a camera is lost (trigger refused, control lost, or
// max_consecutive_misses grabs in a row without a frame), frames stop pairing up
// (max_rounds_without_set), or a write fails (disk full).
//
// Thread safety: Record runs on one thread; RequestStop may be called from any thread or a
// signal handler (it stores to a lock-free atomic).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bcot/capture/frame_source.h"
#include "bcot/core/option_schema.h"
#include "bcot/core/status.h"

namespace bcot {

struct RecorderOptions {
  // Stop after this many frame sets; 0 = until stopped. [0, 1e9]
  int max_frame_sets = 0;
  // Stop after this much time (s); 0 = no limit. [0, 1e7]
  double max_duration_s = 0.0;
  // Frames whose host timestamps differ by at most this much (ms) form a set; keep it below
  // half the frame interval. (0, 1000]
  double max_skew_ms = 10.0;
  // How long to wait for one camera's frame (ms), [1, 60000]. Must exceed the trigger-to-
  // frame delay (exposure + transfer; at a low frame rate, the frame period).
  int grab_timeout_ms = 1000;
  // A camera that misses this many grabs in a row is considered lost, [1, 1000].
  int max_consecutive_misses = 5;
  // Stop with an error after this many rounds in a row that complete no frame set although
  // frames arrive: the cameras are not synchronized (free-running, or a trigger line not
  // wired) or max_skew_ms is too small. [1, 1000000]
  int max_rounds_without_set = 50;
  // zlib level of the written PNGs, [0, 9]: 1 is fast, 9 small.
  int png_compression = 1;
  // rig.yaml to copy into the sequence (from `bcot calibrate`); empty = none (the sequence
  // then needs a rig.yaml before it can be annotated).
  std::string rig_yaml;

  Status Validate() const;  // every violation, kInvalidConfig
};

// The declaration of every recorder option (section `recording` of capture.yaml).
const OptionSchema<RecorderOptions>& RecorderOptionSchema();

struct RecordingStats {
  std::vector<std::string> camera_names;
  int64_t frame_sets = 0;                // committed to disk
  std::vector<int64_t> frames_received;  // per camera: complete frames grabbed
  std::vector<int64_t> missed;           // per camera: grabs without a frame
  std::vector<int64_t> discarded;        // per camera: frames without partners
  double elapsed_s = 0.0;                // since recording started (steady clock)
};

struct RecordingSummary {
  RecordingStats stats;
  // OK when stopped by a limit or RequestStop; else why the recording ended early (camera
  // lost, write failed). Every frame set counted in stats is on disk either way.
  Status status;
  std::string stop_reason;  // "max_frame_sets reached", "stop requested", ...
};

// Called after every round (trigger, grab from each camera, commit what pairs up).
using RecorderProgress = std::function<void(const RecordingStats&)>;

class Recorder {
 public:
  Recorder(std::vector<std::unique_ptr<FrameSource>> sources, RecorderOptions options);
  ~Recorder();

  // Records into `out_dir` (new or empty). Setup failures (output folder, rig mismatch, a
  // camera that does not start) return in `status` with no frame set written.
  RecordingSummary Record(const std::string& out_dir, const RecorderProgress& progress = {});

  void RequestStop() { stop_requested_.store(true); }
  // The flag RequestStop sets, for a signal handler (async-signal-safe when lock-free).
  std::atomic<bool>* stop_flag() { return &stop_requested_; }

 private:
  std::vector<std::unique_ptr<FrameSource>> sources_;
  RecorderOptions options_;
  std::atomic<bool> stop_requested_{false};
};

}  // namespace bcot
