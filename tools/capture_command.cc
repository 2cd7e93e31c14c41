// bcot capture --config configs/capture.yaml --out DIR [--frames N] [--rig rig.yaml]
//              [--set section.key=value]... | --list-devices
// Records synchronized frame sets from Aravis cameras into a sequence directory that stays
// valid whenever the recording stops (see recorder.h). Ctrl-C stops cleanly; a second Ctrl-C
// kills.
#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "bcot/capture/aravis_frame_source.h"
#include "bcot/capture/capture_options.h"
#include "bcot/capture/recorder.h"
#include "bcot/core/file_util.h"
#include "bcot/core/yaml_util.h"
#include "commands.h"

namespace bcot::tools {
namespace {

// The one piece of mutable global state: where SIGINT/SIGTERM deliver the stop request (the
// recorder's own flag while a recording runs). Lock-free atomics are async-signal-safe.
std::atomic<std::atomic<bool>*> signal_stop_flag{nullptr};

extern "C" void OnStopSignal(int) {
  std::atomic<bool>* flag = signal_stop_flag.load();
  if (flag != nullptr) flag->store(true);
}

// Routes SIGINT and SIGTERM to `flag` for its lifetime; the handler resets itself, so a
// second signal terminates as usual.
class StopSignalScope {
 public:
  explicit StopSignalScope(std::atomic<bool>* flag) {
    signal_stop_flag.store(flag);
    struct sigaction action = {};
    action.sa_handler = OnStopSignal;
    action.sa_flags = SA_RESETHAND;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
  }
  ~StopSignalScope() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
    signal_stop_flag.store(nullptr);
  }
  StopSignalScope(const StopSignalScope&) = delete;
  StopSignalScope& operator=(const StopSignalScope&) = delete;

 private:
  struct sigaction old_int_ = {};
  struct sigaction old_term_ = {};
};

// Prints "frames, fps per camera, drops" on stderr: rewritten in place on a terminal at most
// twice a second, otherwise (a log) one line every 5 s.
class StatusLine {
 public:
  void Update(const RecordingStats& stats, bool final_update) {
    const auto now = std::chrono::steady_clock::now();
    const double since = std::chrono::duration<double>(now - last_time_).count();
    if (!final_update && since < (tty_ ? 0.5 : 5.0) && !last_received_.empty()) return;
    std::string cameras;
    for (size_t c = 0; c < stats.camera_names.size(); ++c) {
      const int64_t before = c < last_received_.size() ? last_received_[c] : 0;
      const double fps = since > 0.0 ? (stats.frames_received[c] - before) / since : 0.0;
      cameras += fmt::format("{}{} {:.1f} fps", c == 0 ? "" : ", ", stats.camera_names[c], fps);
    }
    int64_t missed = 0, discarded = 0;
    for (size_t c = 0; c < stats.camera_names.size(); ++c) {
      missed += stats.missed[c];
      discarded += stats.discarded[c];
    }
    const std::string line =
        fmt::format("bcot capture: {} frame sets | {} | missed {} | unmatched {}", stats.frame_sets,
                    cameras, missed, discarded);
    if (tty_) {
      std::fprintf(stderr, "\r%s\033[K%s", line.c_str(), final_update ? "\n" : "");
    } else {
      std::fprintf(stderr, "%s\n", line.c_str());
    }
    last_time_ = now;
    last_received_ = stats.frames_received;
  }

 private:
  bool tty_ = ::isatty(STDERR_FILENO) != 0;
  std::chrono::steady_clock::time_point last_time_ = std::chrono::steady_clock::now();
  std::vector<int64_t> last_received_;
};

struct CaptureFlags {
  ConfigFlags config;
  std::string out_dir;
  std::string rig_yaml;
  int frames = -1;
  bool list_devices = false;
  bool quiet = false;
};

int RunCapture(const CaptureFlags& flags) {
  if (!AravisAvailable()) {
    PrintError("capture", OpenAravisCameras(CaptureOptions()).status().message());
    return 1;
  }
  std::vector<std::string> overrides = flags.config.overrides;
  if (flags.frames >= 0)
    overrides.push_back(fmt::format("recording.max_frame_sets={}", flags.frames));
  if (!flags.rig_yaml.empty()) {
    overrides.push_back("recording.rig_yaml=" +
                        FormatYamlString(std::filesystem::absolute(flags.rig_yaml).string()));
  }
  if (flags.list_devices) {
    bool fake = false;
    if (!flags.config.config_path.empty() || !overrides.empty()) {
      StatusOr<CaptureOptions> options = ReadCaptureOptions(flags.config.config_path, overrides);
      fake = options.ok() && options->aravis.enable_fake_interface;
    }
    const StatusOr<std::vector<std::string>> devices = ListAravisDevices(fake);
    if (!devices.ok()) {
      PrintError("capture", devices.status().message());
      return devices.status().ExitCode();
    }
    for (const std::string& id : *devices) std::printf("%s\n", id.c_str());
    return 0;
  }
  if (flags.out_dir.empty()) {
    PrintError("capture", "--out is required (the sequence directory to write)");
    return 2;
  }
  StatusOr<CaptureOptions> options = ReadCaptureOptions(flags.config.config_path, overrides);
  if (!options.ok()) {
    PrintError("capture", options.status().message());
    return options.status().ExitCode();
  }
  StatusOr<std::vector<std::unique_ptr<FrameSource>>> sources = OpenAravisCameras(*options);
  if (!sources.ok()) {
    PrintError("capture", sources.status().message());
    return sources.status().ExitCode();
  }
  Recorder recorder(std::move(*sources), options->recording);
  StatusLine status_line;
  RecordingSummary summary;
  {
    StopSignalScope stop_on_signal(recorder.stop_flag());
    RecorderProgress progress;
    if (!flags.quiet) {
      progress = [&status_line](const RecordingStats& stats) { status_line.Update(stats, false); };
    }
    summary = recorder.Record(flags.out_dir, progress);
  }
  if (!flags.quiet) status_line.Update(summary.stats, true);
  if (summary.stats.frame_sets > 0 || std::filesystem::exists(flags.out_dir + "/timestamps.csv")) {
    const Status written =
        WriteFileAtomic(flags.out_dir + "/capture.resolved.yaml", FormatCaptureOptions(*options));
    if (!written.ok()) PrintError("capture", written.message());
  }
  if (!summary.status.ok()) {
    PrintError("capture", summary.status.message());
    return summary.status.ExitCode();
  }
  std::fprintf(stderr, "bcot capture: %s; wrote %lld frame sets to %s in %.1f s\n",
               summary.stop_reason.c_str(), static_cast<long long>(summary.stats.frame_sets),
               flags.out_dir.c_str(), summary.stats.elapsed_s);
  return 0;
}

}  // namespace

void AddCaptureCommand(CLI::App& app, int* exit_code) {
  auto flags = std::make_shared<CaptureFlags>();
  CLI::App* command = app.add_subcommand(
      "capture", "Record synchronized frame sets from Aravis cameras into a sequence directory");
  AddConfigFlags(command, &flags->config, CaptureOptionSchema());
  command->add_option("--out", flags->out_dir, "Sequence directory to write (new or empty)");
  command
      ->add_option("--frames", flags->frames,
                   "Stop after this many frame sets (sets recording.max_frame_sets; 0 = until "
                   "Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--rig", flags->rig_yaml,
                      "rig.yaml from `bcot calibrate` to copy into the sequence "
                      "(sets recording.rig_yaml)");
  command->add_flag("--list-devices", flags->list_devices,
                    "Print the Aravis device ids found and exit");
  command->add_flag("--quiet", flags->quiet, "No status line on stderr");
  command->callback([flags, exit_code] { *exit_code = RunCapture(*flags); });
}

}  // namespace bcot::tools
