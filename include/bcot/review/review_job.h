// The long tasks `bcot review` runs for its page (re-annotating a range of frames, searching an
// initial pose) on a thread of their own, one at a time, with their progress readable while
// they run (GET /api/job). The HTTP handlers only start a job and poll it.
#pragma once

#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "bcot/core/status.h"

namespace bcot {

class ReviewJob {
 public:
  // Reports (steps done, steps in total) while the work runs.
  using Progress = std::function<void(int done, int total)>;
  // The work: its Status ends the job ("done" with the returned message, or "failed" with the
  // error's).
  using Work = std::function<StatusOr<std::string>(const Progress& progress)>;

  ReviewJob() = default;
  ReviewJob(const ReviewJob&) = delete;
  ReviewJob& operator=(const ReviewJob&) = delete;
  // Waits for a running job.
  ~ReviewJob();

  // Starts `work` on its own thread under `name` (e.g. "re-annotate 4:9"); kInvalidInput naming
  // the running job when one has not finished yet.
  Status Start(const std::string& name, Work work);
  // {"name", "state": "idle" | "running" | "done" | "failed", "run": the count of jobs started,
  // "done", "total" (steps; 0 / 0 until the work reports), "message"}.
  std::string Json() const;
  bool Running() const;

 private:
  mutable std::mutex mutex_;
  std::thread thread_;
  std::string name_;
  std::string state_ = "idle";
  int run_ = 0;
  int done_ = 0;
  int total_ = 0;
  std::string message_;
};

}  // namespace bcot
