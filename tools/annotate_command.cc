// bcot annotate <sequence dir> --out DIR [--keyframes FILE] [--frames A:B] [--config FILE]
//               [--set section.key=value]... [--overwrite] [--image-cache-mb N] [--quiet]
// Annotates one sequence (see bcot/annotate/annotator.h) with a progress line on stderr.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "bcot/annotate/annotate_options.h"
#include "bcot/annotate/annotator.h"
#include "bcot/quality/quality_files.h"
#include "commands.h"
#include "progress_line.h"

namespace bcot::tools {
namespace {

struct AnnotateFlags {
  ConfigFlags config;
  std::string sequence_dir;
  std::string out_dir;
  AnnotateInputs inputs;
  bool quiet = false;
};

int RunAnnotate(const AnnotateFlags& flags) {
  StatusOr<AnnotateOptions> options =
      ReadAnnotateOptions(flags.config.config_path, flags.config.overrides);
  if (!options.ok()) {
    PrintError("annotate", options.status().message());
    return options.status().ExitCode();
  }
  const auto start = std::chrono::steady_clock::now();
  ProgressLine line(!flags.quiet);
  AnnotateProgress progress;
  if (!flags.quiet) {
    progress = [start, &line](int done, int total) {
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double fps = done / std::max(seconds, 1e-9);
      const double eta = (total - done) / std::max(fps, 1e-9);
      line.Update(fmt::format("bcot annotate: frame {}/{}  {:.2f} fps  ETA {:.0f} s", done, total,
                              fps, eta),
                  done == total);
    };
  }
  const StatusOr<AnnotationOutcome> outcome =
      AnnotateSequenceDir(flags.sequence_dir, flags.out_dir, *options, flags.inputs, progress);
  if (!outcome.ok()) {
    line.Break();
    PrintError("annotate", outcome.status().message());
    return outcome.status().ExitCode();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "bcot annotate: wrote %s in %.1f s\n", flags.out_dir.c_str(), seconds);
  for (const std::string& note : outcome->notes) {
    std::fprintf(stderr, "bcot annotate: note: %s\n", note.c_str());
  }
  // A rejection says why (the first reason: view, bad frames, worst error or an invisible
  // boundary); an acceptance its worst error.
  const QualityVerdict& verdict = outcome->verdict;
  const std::string detail = !verdict.accepted && !verdict.reasons.empty()
                                 ? ": " + verdict.reasons.front()
                                 : fmt::format(" (worst {:.2f} px)", verdict.worst_px);
  std::fprintf(stderr, "bcot annotate: quality %s%s; see %s/report.html\n",
               verdict.accepted ? "accepted" : "rejected", detail.c_str(), flags.out_dir.c_str());
  return verdict.accepted ? 0 : kExitRejected;
}

}  // namespace

void AddAnnotateCommand(CLI::App& app, int* exit_code) {
  auto flags = std::make_shared<AnnotateFlags>();
  CLI::App* command = app.add_subcommand(
      "annotate", "Annotate one sequence directory: joint multi-view pose per frame");
  command->add_option("sequence", flags->sequence_dir, "Sequence directory (holds rig.yaml)")
      ->required();
  AddConfigFlags(command, &flags->config, AnnotateOptionSchema());
  command->add_option("--out", flags->out_dir, "Annotation output directory")->required();
  command->add_option("--keyframes", flags->inputs.keyframes_path,
                      "Keyframes file (lines: frame, then a rig_from_object pose line) in place "
                      "of <sequence>/keyframes.txt");
  command->add_option("--frames", flags->inputs.frames,
                      "A:B: re-annotate frames A..B (inclusive) of the finished annotation in "
                      "--out and splice them in");
  command->add_flag("--overwrite", flags->inputs.overwrite,
                    "Write into an --out that holds files bcot annotate does not write (they "
                    "are left alone); without it such a directory is refused");
  command
      ->add_option("--image-cache-mb", flags->inputs.image_cache_mb,
                   "Decoded frames kept in memory (MiB) so the quality check does not decode "
                   "them again; 0 = none")
      ->capture_default_str()
      ->check(CLI::Range(size_t{0}, size_t{1} << 30));
  command->add_flag("--quiet", flags->quiet, "No progress on stderr");
  command->callback([flags, exit_code] { *exit_code = RunAnnotate(*flags); });
}

}  // namespace bcot::tools
