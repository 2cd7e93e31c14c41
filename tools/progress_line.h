// The progress line of a command's long loop (annotate, batch) on stderr. On a terminal it is
// rewritten in place ("\r") at most every `tty_interval_s`; elsewhere (a pipe, a Slurm log) it
// is a full line at most every `log_interval_s`, so logs hold no carriage returns. The final
// update is always shown. A disabled line (--quiet) prints nothing.
#pragma once

#include <chrono>
#include <string>

namespace bcot::tools {

class ProgressLine {
 public:
  struct Options {
    double tty_interval_s = 0.2;
    double log_interval_s = 5.0;
  };
  explicit ProgressLine(bool enabled) : ProgressLine(enabled, Options()) {}
  ProgressLine(bool enabled, const Options& options);

  // Shows `text` if the interval has passed since the last shown update, or if `final_update`.
  void Update(const std::string& text, bool final_update);
  // Ends a line rewritten in place with a newline (before an error or a summary line).
  void Break();

 private:
  bool enabled_;
  bool tty_;
  Options options_;
  bool showing_ = false;  // a line rewritten in place is on the terminal, without newline
  std::chrono::steady_clock::time_point last_shown_;
  bool shown_once_ = false;
};

}  // namespace bcot::tools
