#include "progress_line.h"

#include <unistd.h>

#include <cstdio>

namespace bcot::tools {

ProgressLine::ProgressLine(bool enabled, const Options& options)
    : enabled_(enabled), tty_(::isatty(STDERR_FILENO) != 0), options_(options) {}

void ProgressLine::Update(const std::string& text, bool final_update) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double interval = tty_ ? options_.tty_interval_s : options_.log_interval_s;
  if (!final_update && shown_once_ &&
      std::chrono::duration<double>(now - last_shown_).count() < interval) {
    return;
  }
  last_shown_ = now;
  shown_once_ = true;
  if (tty_) {
    std::fprintf(stderr, "\r%s\033[K", text.c_str());  // ESC[K clears a longer previous line
    showing_ = !final_update;
    if (final_update) std::fprintf(stderr, "\n");
  } else {
    std::fprintf(stderr, "%s\n", text.c_str());
  }
}

void ProgressLine::Break() {
  if (!showing_) return;
  std::fprintf(stderr, "\n");
  showing_ = false;
}

}  // namespace bcot::tools
