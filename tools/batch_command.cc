// bcot batch <root> --out DIR [--config FILE] [--set section.key=value]... [--jobs N]
//            [--shard k/N] [--force] [--in-process] [--image-cache-mb N]
// Annotates every sequence under <root> (see bcot/annotate/batch.h) with a live progress line on
// stderr, each sequence in its own `bcot annotate` process (child_process_runner.h) unless
// --in-process; exit 0 when every sequence succeeded, 1 when any failed, 2 for usage/config
// errors.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "bcot/annotate/annotate_options.h"
#include "bcot/annotate/batch.h"
#include "bcot/annotate/child_process_runner.h"
#include "commands.h"
#include "progress_line.h"

namespace bcot::tools {
namespace {

struct BatchFlags {
  ConfigFlags config;
  std::string root;
  std::string out_dir;
  int jobs = 0;
  std::string shard = "0/1";
  bool force = false;
  bool quiet = false;
  bool in_process = false;
  size_t image_cache_mb = BatchOptions().image_cache_mb;
};

std::string FormatProgress(const BatchProgress& p) {
  const double fps = p.frames_done / std::max(p.seconds, 1e-9);
  const double eta = (p.frames_total - p.frames_done) / std::max(fps, 1e-9);
  return fmt::format(
      "bcot batch: {}/{} sequences ({} skipped, {} failed)  {}/{} frames  {:.2f} frames/s  ETA {}",
      p.sequences_done, p.sequences_total, p.sequences_skipped, p.sequences_failed, p.frames_done,
      p.frames_total, fps, p.frames_done > 0 ? fmt::format("{:.0f} s", eta) : "?");
}

int RunBatchCommand(const BatchFlags& flags) {
  StatusOr<AnnotateOptions> annotate =
      ReadAnnotateOptions(flags.config.config_path, flags.config.overrides);
  if (!annotate.ok()) {
    PrintError("batch", annotate.status().message());
    return annotate.status().ExitCode();
  }
  BatchOptions options;
  options.annotate = *annotate;
  options.jobs = flags.jobs;
  options.force = flags.force;
  options.image_cache_mb = flags.image_cache_mb;
  if (!flags.in_process) {
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error) {
      PrintError("batch", "cannot find the bcot executable (/proc/self/exe: " + error.message() +
                              "); use --in-process");
      return 1;
    }
    options.runner = MakeChildProcessRunner(
        self.string(), {"--image-cache-mb", std::to_string(flags.image_cache_mb)});
  }
  const Status shard = ParseShard(flags.shard, &options);
  if (!shard.ok()) {
    PrintError("batch", shard.message());
    return shard.ExitCode();
  }
  ProgressLine line(!flags.quiet, {/*tty_interval_s=*/0.5, /*log_interval_s=*/10.0});
  BatchProgressCallback progress;
  if (!flags.quiet) {
    progress = [&line](const BatchProgress& p) {
      line.Update(FormatProgress(p), p.sequences_done == p.sequences_total);
    };
  }
  const StatusOr<BatchResult> result = RunBatch(flags.root, flags.out_dir, options, progress);
  line.Break();
  if (!result.ok()) {
    PrintError("batch", result.status().message());
    return result.status().ExitCode();
  }
  int annotated = 0, skipped = 0, accepted = 0, rejected = 0;
  for (const BatchSequenceResult& s : result->sequences) {
    annotated += s.outcome == BatchOutcome::kAnnotated;
    skipped += s.outcome == BatchOutcome::kSkipped;
    if (s.outcome == BatchOutcome::kFailed) {
      std::fprintf(stderr, "bcot batch: %s failed: %s\n", s.relative_path.c_str(), s.error.c_str());
    } else {
      (s.accepted ? accepted : rejected) += 1;
    }
  }
  std::fprintf(stderr,
               "bcot batch: %d annotated, %d skipped, %d failed; %d accepted, %d rejected; "
               "summary: %s/summary.html\n",
               annotated, skipped, result->num_failed(), accepted, rejected, flags.out_dir.c_str());
  return result->ExitCode();
}

}  // namespace

void AddBatchCommand(CLI::App& app, int* exit_code) {
  auto flags = std::make_shared<BatchFlags>();
  CLI::App* command = app.add_subcommand(
      "batch", "Annotate every sequence (folder holding rig.yaml) under a directory tree");
  command->add_option("root", flags->root, "Directory tree of sequences")->required();
  AddConfigFlags(command, &flags->config, AnnotateOptionSchema());
  command->add_option("--out", flags->out_dir, "Output root (mirrors the input tree)")->required();
  command->add_option("--jobs", flags->jobs, "Sequences in parallel (0 = one per core)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command
      ->add_option("--shard", flags->shard,
                   "Process shard k of N (0 <= k < N), e.g. $SLURM_ARRAY_TASK_ID/N")
      ->capture_default_str();
  command
      ->add_option("--image-cache-mb", flags->image_cache_mb,
                   "Decoded frames each running sequence keeps in memory (MiB) for its quality "
                   "check; 0 = none")
      ->capture_default_str()
      ->check(CLI::Range(size_t{0}, size_t{1} << 30));
  command->add_flag("--force", flags->force, "Redo sequences whose DONE matches");
  command->add_flag("--quiet", flags->quiet, "No progress on stderr");
  command->add_flag("--in-process", flags->in_process,
                    "Annotate in this process (default: one child process per sequence, so a "
                    "crash fails only that sequence)");
  command->callback([flags, exit_code] { *exit_code = RunBatchCommand(*flags); });
}

}  // namespace bcot::tools
