#include "bcot/annotate/child_process_runner.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "bcot/annotate/done_file.h"
#include "bcot/core/file_util.h"
#include "bcot/quality/quality_files.h"

namespace bcot {
namespace {

// Reads the child's output: "frame d/N" segments (ended by '\r' or '\n') drive `progress`;
// the last non-empty line is kept.
class ChildOutput {
 public:
  explicit ChildOutput(const AnnotateProgress& progress) : progress_(progress) {}

  void Consume(const char* data, size_t size) {
    for (size_t i = 0; i < size; ++i) {
      if (data[i] == '\r' || data[i] == '\n') {
        EndSegment();
      } else {
        segment_ += data[i];
      }
    }
  }
  void Finish() { EndSegment(); }
  const std::string& last_line() const { return last_line_; }
  // The child's notes (AnnotationOutcome::notes), without their "bcot annotate: note: " prefix.
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  void EndSegment() {
    int done = 0, total = 0;
    const size_t at = segment_.find("frame ");
    if (at != std::string::npos &&
        std::sscanf(segment_.c_str() + at, "frame %d/%d", &done, &total) == 2) {
      if (progress_) progress_(done, total);
    } else if (segment_.find_first_not_of(" \t") != std::string::npos) {
      last_line_ = segment_;
      constexpr std::string_view kNotePrefix = "bcot annotate: note: ";
      if (segment_.rfind(kNotePrefix, 0) == 0)
        notes_.push_back(segment_.substr(kNotePrefix.size()));
    }
    segment_.clear();
  }

  const AnnotateProgress& progress_;
  std::string segment_;
  std::string last_line_;
  std::vector<std::string> notes_;
};

std::string SignalName(int signal) {
  const char* name = ::strsignal(signal);
  return name != nullptr ? name : "unknown";
}

// Runs argv[0] with `argv`, its stdout and stderr into `output`; returns the wait status.
StatusOr<int> RunChild(const std::vector<std::string>& argv, ChildOutput* output) {
  std::vector<char*> args;
  for (const std::string& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
  args.push_back(nullptr);
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    return Status::IoError(fmt::format("cannot create a pipe: {}", std::strerror(errno)));
  }
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    return Status::IoError(fmt::format("cannot start a process: {}", std::strerror(error)));
  }
  if (pid == 0) {
    // Child: only async-signal-safe calls until exec.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // the batch died before prctl
    ::dup2(fds[1], STDOUT_FILENO);
    ::dup2(fds[1], STDERR_FILENO);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  ::close(fds[1]);
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fds[0], buffer, sizeof(buffer));
    if (n > 0) {
      output->Consume(buffer, static_cast<size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(fds[0]);
  output->Finish();
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      return Status::Internal(
          fmt::format("cannot wait for process {}: {}", pid, std::strerror(errno)));
    }
  }
  return status;
}

}  // namespace

SequenceRunner MakeChildProcessRunner(const std::string& executable,
                                      const std::vector<std::string>& extra_arguments) {
  return [executable, extra_arguments](
             const std::string& sequence_dir, const std::string& annotation_dir,
             const AnnotateOptions& options,
             const AnnotateProgress& progress) -> StatusOr<AnnotationOutcome> {
    const std::string config = annotation_dir + "/.batch_config.yaml";
    BCOT_RETURN_IF_ERROR(WriteFileAtomic(config, FormatAnnotateOptions(options)));
    ChildOutput output(progress);
    std::vector<std::string> arguments = {executable,     "annotate", sequence_dir, "--out",
                                          annotation_dir, "--config", config};
    arguments.insert(arguments.end(), extra_arguments.begin(), extra_arguments.end());
    const StatusOr<int> status = RunChild(arguments, &output);
    std::error_code ignored;
    std::filesystem::remove(config, ignored);
    if (!status.ok()) return status.status();
    const std::string last = output.last_line().empty() ? "" : ": " + output.last_line();
    if (WIFSIGNALED(*status)) {
      const int signal = WTERMSIG(*status);
      return Status::Internal(fmt::format("the annotation process was killed by signal {} ({}){}",
                                          signal, SignalName(signal), last));
    }
    const int code = WIFEXITED(*status) ? WEXITSTATUS(*status) : -1;
    if (code == 127 && output.last_line().empty()) {
      return Status::Internal(fmt::format("{}: cannot be run", executable));
    }
    if (code != 0 && code != kExitRejected) {
      // The child's own message, without its "bcot annotate: error: " prefix.
      std::string message = output.last_line();
      const std::string prefix = "bcot annotate: error: ";
      if (message.rfind(prefix, 0) == 0) message = message.substr(prefix.size());
      if (message.empty()) message = fmt::format("the annotation process exited with {}", code);
      return code == 2 ? Status::InvalidConfig(message) : Status::InvalidInput(message);
    }
    BCOT_ASSIGN_OR_RETURN(const DoneRecord done, ReadDoneFile(annotation_dir));
    BCOT_ASSIGN_OR_RETURN(const QualityVerdict verdict, ReadQualityVerdict(annotation_dir));
    AnnotationOutcome outcome;
    outcome.verdict = verdict;
    outcome.frames = done.frames;
    outcome.failed_frames = done.failed_frames;
    outcome.notes = output.notes();
    return outcome;
  };
}

}  // namespace bcot
