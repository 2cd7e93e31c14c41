#include "bcot/review/review_job.h"

#include <nlohmann/json.hpp>

namespace bcot {

ReviewJob::~ReviewJob() {
  if (thread_.joinable()) thread_.join();
}

bool ReviewJob::Running() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return state_ == "running";
}

Status ReviewJob::Start(const std::string& name, Work work) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (state_ == "running") {
    return Status::InvalidInput("'" + name_ + "' is still running; wait for it to finish");
  }
  // The previous job has ended (its state was set as its last step): its thread only returns.
  if (thread_.joinable()) thread_.join();
  name_ = name;
  state_ = "running";
  ++run_;
  done_ = total_ = 0;
  message_.clear();
  thread_ = std::thread([this, work = std::move(work)] {
    const Progress progress = [this](int done, int total) {
      std::lock_guard<std::mutex> inner(mutex_);
      done_ = done;
      total_ = total;
    };
    const StatusOr<std::string> result = work(progress);
    std::lock_guard<std::mutex> inner(mutex_);
    state_ = result.ok() ? "done" : "failed";
    message_ = result.ok() ? *result : result.status().message();
  });
  return Status::Ok();
}

std::string ReviewJob::Json() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return nlohmann::ordered_json{{"name", name_}, {"state", state_}, {"run", run_},
                                {"done", done_}, {"total", total_}, {"message", message_}}
      .dump();
}

}  // namespace bcot
