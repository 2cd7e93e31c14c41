// bcot export ANN --sequence SEQ --out ROOT [--format bcot|bop] [--preset bcot-release]
//             [--frames A:B] [--frame-step N] [--include-rejected] [--quiet]
//             [--config configs/export.yaml] [--set key=value]... [--overwrite]
// Writes an annotated sequence in the BCOT release layout (exporter.h) or the BOP layout
// (bop_writer.h); docs/export.md. Options are resolved as: preset, then --config, then --set,
// then the flags --format, --frames, --frame-step and --overwrite. Exit codes: 0 exported,
// kExitRejected (3) for a rejected annotation without --include-rejected, 2 usage or
// configuration error, 1 any other failure.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "bcot/core/status.h"
#include "bcot/export/exporter.h"
#include "bcot/quality/quality_files.h"
#include "commands.h"

namespace bcot::tools {
namespace {

struct ExportFlags {
  ConfigFlags config;
  std::string sequence_dir;
  std::string annotation_dir;
  std::string out_root;
  std::string format;
  std::string preset;
  std::string frames;  // "A:B" or "A:"
  int frame_step = 0;  // 0 = not given
  bool include_rejected = false;
  bool overwrite = false;
  bool quiet = false;
};

// --frames "A:B" (frames A..B inclusive, 0-based, as `bcot annotate --frames`) or "A:" (A to
// the end); `last` is -1 for "A:". Empty when malformed.
struct FrameRangeFlag {
  int first = 0;
  int last = -1;
};

std::optional<int> ParseFrameNumber(const std::string& digits) {
  if (digits.empty() || digits.size() > 9) return std::nullopt;
  for (const char c : digits) {
    if (c < '0' || c > '9') return std::nullopt;
  }
  return std::stoi(digits);
}

std::optional<FrameRangeFlag> ParseFrameRangeFlag(const std::string& text) {
  const size_t colon = text.find(':');
  if (colon == std::string::npos) return std::nullopt;
  const std::optional<int> first = ParseFrameNumber(text.substr(0, colon));
  if (!first.has_value()) return std::nullopt;
  const std::string rest = text.substr(colon + 1);
  if (rest.empty()) return FrameRangeFlag{*first, -1};
  const std::optional<int> last = ParseFrameNumber(rest);
  if (!last.has_value()) return std::nullopt;
  return FrameRangeFlag{*first, *last};
}

// CLI11 validator of --frames: "" when `text` is A:B with B >= A, or A:.
std::string FrameRangeProblem(const std::string& text) {
  const std::optional<FrameRangeFlag> range = ParseFrameRangeFlag(text);
  if (!range.has_value()) {
    return fmt::format("--frames '{}': expected A:B (frames A to B, 0-based) or A: (A to the end)",
                       text);
  }
  if (range->last >= 0 && range->last < range->first) {
    return fmt::format("--frames '{}': B must not be less than A", text);
  }
  return "";
}

// The flags that set options, as `key=value` overrides applied after --set.
std::vector<std::string> FlagOverrides(const ExportFlags& flags) {
  std::vector<std::string> overrides = flags.config.overrides;
  if (!flags.format.empty()) overrides.push_back("format=" + flags.format);
  if (flags.frame_step > 0) overrides.push_back(fmt::format("frame_step={}", flags.frame_step));
  if (!flags.frames.empty()) {
    const std::optional<FrameRangeFlag> range = ParseFrameRangeFlag(flags.frames);
    BCOT_CHECK(range.has_value());  // validated by CLI11
    overrides.push_back(fmt::format("first_frame={}", range->first));
    // end_frame is exclusive; -1 = to the end.
    overrides.push_back(fmt::format("end_frame={}", range->last < 0 ? -1 : range->last + 1));
  }
  if (flags.overwrite) overrides.push_back("overwrite=true");
  return overrides;
}

// A rejected annotation (quality.json's verdict) is exported only with --include-rejected:
// returns 0 to go on, else the exit code (kExitRejected, or that of an unreadable quality.json)
// after printing why. An annotation without quality.json (e.g. synthetic ground truth) has no
// verdict to check.
int CheckVerdict(const std::string& annotation_dir, bool include_rejected, bool quiet) {
  std::error_code error;
  if (!std::filesystem::exists(annotation_dir + "/quality.json", error)) return 0;
  const StatusOr<QualityVerdict> verdict = ReadQualityVerdict(annotation_dir);
  if (!verdict.ok()) {
    PrintError("export", verdict.status().message());
    return verdict.status().ExitCode();
  }
  if (verdict->accepted) return 0;
  const std::string reasons = verdict->reasons.empty()
                                  ? "no reason recorded"
                                  : fmt::format("{}", fmt::join(verdict->reasons, "; "));
  if (include_rejected) {
    if (!quiet) {
      std::fprintf(stderr, "bcot export: exporting %s although its verdict is rejected (%s)\n",
                   annotation_dir.c_str(), reasons.c_str());
    }
    return 0;
  }
  PrintError("export", fmt::format("{}: verdict rejected in its quality.json ({}); pass "
                                   "--include-rejected to export it anyway",
                                   annotation_dir, reasons));
  return kExitRejected;
}

int RunExport(const ExportFlags& flags) {
  StatusOr<ExportOptions> options = ExportPreset(flags.preset);
  if (options.ok()) {
    options = ReadExportOptions(flags.config.config_path, FlagOverrides(flags), *options);
  }
  if (!options.ok()) {
    PrintError("export", options.status().message());
    return options.status().ExitCode();
  }
  const int verdict = CheckVerdict(flags.annotation_dir, flags.include_rejected, flags.quiet);
  if (verdict != 0) return verdict;
  const StatusOr<ExportSummary> summary =
      ExportAnnotation(flags.sequence_dir, flags.annotation_dir, flags.out_root, *options);
  if (!summary.ok()) {
    PrintError("export", summary.status().message());
    return summary.status().ExitCode();
  }
  if (!flags.quiet) {
    std::fprintf(stderr, "bcot export: %s\n", DescribeExport(*summary, options->format).c_str());
  }
  return 0;
}

}  // namespace

void AddExportCommand(CLI::App& app, int* exit_code) {
  auto flags = std::make_shared<ExportFlags>();
  CLI::App* command = app.add_subcommand(
      "export", "Write an annotated sequence as a dataset: the BCOT release layout or BOP");
  AddConfigFlags(command, &flags->config, ExportOptionSchema());
  command
      ->add_option("annotation", flags->annotation_dir,
                   "Annotation directory of the sequence (its rig_from_object.txt; "
                   "quality.json's verdict is checked)")
      ->required();
  command->add_option("--sequence", flags->sequence_dir, "Sequence directory (rig.yaml, frames)")
      ->required();
  command->add_option("--out", flags->out_root, "Root of the dataset tree")->required();
  command->add_option("--format", flags->format, "bcot (default) or bop (same as --set format=)")
      ->check(CLI::IsMember({"bcot", "bop"}));
  command
      ->add_option("--preset", flags->preset,
                   "Starting options before --config/--set: bcot-release = the paper's release "
                   "(every 2nd frame, half resolution); default: every frame, full resolution")
      ->check(CLI::IsMember(ExportPresetNames()));
  command
      ->add_option("--frames", flags->frames,
                   "Frames A:B (A to B, 0-based, inclusive) or A: (to the end); default: all")
      ->check(CLI::Validator([](std::string& text) { return FrameRangeProblem(text); }, "A:B",
                             "frame range"));
  command->add_option("--frame-step", flags->frame_step, "Keep every N-th frame (default 1)")
      ->check(CLI::Range(1, 1000));
  command->add_flag("--include-rejected", flags->include_rejected,
                    "Export an annotation its quality report rejected");
  command->add_flag("--overwrite", flags->overwrite, "Replace an existing output folder");
  command->add_flag("--quiet", flags->quiet, "No summary line on stderr (errors only)");
  command->callback([flags, exit_code] { *exit_code = RunExport(*flags); });
}

}  // namespace bcot::tools
