#include "bcot/capture/recorder.h"

#include <fmt/format.h>

#include <chrono>

#include "bcot/capture/frame_set_matcher.h"
#include "bcot/capture/sequence_writer.h"

namespace bcot {

static_assert(std::atomic<bool>::is_always_lock_free, "the stop flag must be signal-safe");

const OptionSchema<RecorderOptions>& RecorderOptionSchema() {
  static const OptionSchema<RecorderOptions>* const schema = [] {
    auto* s = new OptionSchema<RecorderOptions>();
    s->Add(
         "recording.max_frame_sets", [](auto& o) -> auto& { return o.max_frame_sets; }, "",
         "stop after this many frame sets; 0 = until stopped")
        .Range(Closed(0, 1e9));
    s->Add(
         "recording.max_duration_s", [](auto& o) -> auto& { return o.max_duration_s; }, "s",
         "stop after this much time; 0 = no limit")
        .Range(Closed(0, 1e7));
    s->Add(
         "recording.max_skew_ms", [](auto& o) -> auto& { return o.max_skew_ms; }, "ms",
         "frames whose host timestamps differ by at most this form a set")
        .Range(LeftOpen(0, 1000));
    s->Add(
         "recording.grab_timeout_ms", [](auto& o) -> auto& { return o.grab_timeout_ms; }, "ms",
         "how long to wait for one camera's frame")
        .Range(Closed(1, 60000));
    s->Add(
         "recording.max_consecutive_misses",
         [](auto& o) -> auto& { return o.max_consecutive_misses; }, "",
         "a camera that misses this many grabs in a row is lost")
        .Range(Closed(1, 1000));
    s->Add(
         "recording.max_rounds_without_set",
         [](auto& o) -> auto& { return o.max_rounds_without_set; }, "",
         "stop when this many rounds in a row complete no frame set")
        .Range(Closed(1, 1e6));
    s->Add(
         "recording.png_compression", [](auto& o) -> auto& { return o.png_compression; }, "",
         "zlib level of the written PNGs (1 fast, 9 small)")
        .Range(Closed(0, 9));
    s->Add(
         "recording.rig_yaml", [](auto& o) -> auto& { return o.rig_yaml; }, "",
         "rig.yaml to copy into the sequence (relative to the config file); empty = none")
        .Path();
    return s;
  }();
  return *schema;
}

Status RecorderOptions::Validate() const { return RecorderOptionSchema().Validate(*this, nullptr); }

Recorder::Recorder(std::vector<std::unique_ptr<FrameSource>> sources, RecorderOptions options)
    : sources_(std::move(sources)), options_(std::move(options)) {
  BCOT_CHECK(!sources_.empty());
}

Recorder::~Recorder() {
  for (auto& source : sources_) source->Stop();
}

RecordingSummary Recorder::Record(const std::string& out_dir, const RecorderProgress& progress) {
  RecordingSummary summary;
  RecordingStats& stats = summary.stats;
  const int n = static_cast<int>(sources_.size());
  for (const auto& source : sources_) stats.camera_names.push_back(source->name());
  stats.frames_received.assign(n, 0);
  stats.missed.assign(n, 0);
  stats.discarded.assign(n, 0);

  summary.status = options_.Validate();
  if (!summary.status.ok()) return summary;
  StatusOr<std::unique_ptr<SequenceWriter>> writer = SequenceWriter::Create(
      out_dir, stats.camera_names, options_.rig_yaml, options_.png_compression);
  if (!writer.ok()) {
    summary.status = writer.status();
    return summary;
  }
  for (auto& source : sources_) {
    summary.status = source->Start();
    if (!summary.status.ok()) return summary;
  }

  FrameSetMatcher matcher(n, static_cast<int64_t>(options_.max_skew_ms * 1e6));
  std::vector<int> consecutive_misses(n, 0);
  int rounds_without_set = 0;
  const auto start = std::chrono::steady_clock::now();
  const auto lost = [&](int c, const std::string& why) {
    summary.status = Status::IoError(
        fmt::format("camera '{}' ({}) lost: {}; recording stopped after {} frame sets",
                    sources_[c]->name(), sources_[c]->description(), why, stats.frame_sets));
    summary.stop_reason = "camera lost";
  };

  while (summary.stop_reason.empty()) {
    stats.elapsed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (stop_requested_.load()) {
      summary.stop_reason = "stop requested";
    } else if (options_.max_frame_sets > 0 && stats.frame_sets >= options_.max_frame_sets) {
      summary.stop_reason = "max_frame_sets reached";
    } else if (options_.max_duration_s > 0.0 && stats.elapsed_s >= options_.max_duration_s) {
      summary.stop_reason = "max_duration_s reached";
    }
    if (!summary.stop_reason.empty()) break;

    for (int c = 0; c < n && summary.stop_reason.empty(); ++c) {
      const Status triggered = sources_[c]->Trigger();
      if (!triggered.ok()) lost(c, "trigger refused: " + triggered.message());
    }
    for (int c = 0; c < n && summary.stop_reason.empty(); ++c) {
      GrabResult grab = sources_[c]->Grab(options_.grab_timeout_ms);
      switch (grab.status) {
        case GrabStatus::kFrame:
          ++stats.frames_received[c];
          consecutive_misses[c] = 0;
          matcher.Add(c, std::move(grab.frame));
          break;
        case GrabStatus::kMissed:
          ++stats.missed[c];
          if (++consecutive_misses[c] >= options_.max_consecutive_misses) {
            lost(c, fmt::format("no frame in {} grabs in a row ({})", consecutive_misses[c],
                                grab.message));
          }
          break;
        case GrabStatus::kLost:
          lost(c, grab.message);
          break;
      }
    }
    // Commit what pairs up, even when the round ended with a loss.
    bool committed = false;
    while (std::optional<std::vector<Frame>> set = matcher.PopSet()) {
      if (options_.max_frame_sets > 0 && stats.frame_sets >= options_.max_frame_sets) break;
      const Status appended = (*writer)->Append(*set);
      if (!appended.ok()) {
        summary.status = appended;
        summary.stop_reason = "write failed";
        break;
      }
      ++stats.frame_sets;
      committed = true;
    }
    rounds_without_set = committed ? 0 : rounds_without_set + 1;
    if (summary.stop_reason.empty() && rounds_without_set >= options_.max_rounds_without_set) {
      summary.status = Status::IoError(fmt::format(
          "no frame set in {} rounds although frames arrive: the cameras are not synchronized "
          "(free-running, or the trigger line is not wired) or recording.max_skew_ms = {} is "
          "too small; recording stopped after {} frame sets",
          rounds_without_set, options_.max_skew_ms, stats.frame_sets));
      summary.stop_reason = "cameras not synchronized";
    }
    for (int c = 0; c < n; ++c) stats.discarded[c] = matcher.discarded(c);
    if (progress) progress(stats);
  }
  for (auto& source : sources_) source->Stop();
  stats.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace bcot
