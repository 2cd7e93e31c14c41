// bcot report <annotation dir> [--sequence DIR] [--config FILE] [--set quality.key=value]...
// [--quiet]
// Regenerates quality.json, quality.csv and report.html from the stored poses without
// re-solving. Given a batch output root (no config.resolved.yaml in it), regenerates every
// annotation directory below it and summary.json / summary.html.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "bcot/annotate/batch.h"
#include "bcot/annotate/regenerate_report.h"
#include "bcot/quality/quality_files.h"
#include "bcot/quality/quality_options.h"
#include "bcot/quality/quality_report.h"
#include "commands.h"

namespace bcot::tools {
namespace {

struct ReportFlags {
  std::string annotation_dir;
  std::string sequence_dir;
  ConfigFlags config;
  bool quiet = false;
};

int RunReport(const ReportFlags& flags) {
  if (std::filesystem::exists(flags.annotation_dir + "/config.resolved.yaml") ||
      std::filesystem::exists(flags.annotation_dir + "/DONE")) {
    const StatusOr<QualityReport> report = RegenerateQualityReport(
        flags.annotation_dir, flags.sequence_dir, flags.config.config_path, flags.config.overrides);
    if (!report.ok()) {
      PrintError("report", report.status().message());
      return report.status().ExitCode();
    }
    std::fprintf(stderr, "bcot report: %s: %s; report: %s/report.html\n",
                 flags.annotation_dir.c_str(), report->accepted ? "accepted" : "rejected",
                 flags.annotation_dir.c_str());
    if (!flags.quiet) {
      for (const std::string& reason : report->reasons) {
        std::fprintf(stderr, "  %s\n", reason.c_str());
      }
      for (const std::string& note : SaturationWarnings(*report)) {
        std::fprintf(stderr, "bcot report: note: %s\n", note.c_str());
      }
    }
    return report->accepted ? 0 : kExitRejected;
  }
  if (!flags.sequence_dir.empty()) {
    PrintError("report", "--sequence needs one annotation directory (with config.resolved.yaml)");
    return 2;
  }
  const StatusOr<BatchResult> result = RegenerateBatchReports(
      flags.annotation_dir, flags.config.config_path, flags.config.overrides);
  if (!result.ok()) {
    PrintError("report", result.status().message());
    return result.status().ExitCode();
  }
  for (const BatchSequenceResult& s : result->sequences) {
    if (flags.quiet) break;
    std::fprintf(stderr, "bcot report: %s: %s\n", s.relative_path.c_str(),
                 s.outcome == BatchOutcome::kFailed ? ("failed: " + s.error).c_str()
                 : s.accepted                       ? "accepted"
                                                    : "rejected");
  }
  std::fprintf(stderr, "bcot report: summary: %s/summary.html\n", flags.annotation_dir.c_str());
  return result->ExitCode();
}

}  // namespace

void AddReportCommand(CLI::App& app, int* exit_code) {
  auto flags = std::make_shared<ReportFlags>();
  CLI::App* command = app.add_subcommand(
      "report", "Regenerate quality reports of an annotation (or batch output) without solving");
  command
      ->add_option("annotation", flags->annotation_dir,
                   "Annotation directory, or the output root of `bcot batch`")
      ->required()
      ->check(CLI::ExistingDirectory);
  command->add_option("--sequence", flags->sequence_dir,
                      "Sequence directory (default: as recorded in config.resolved.yaml)");
  // --config replaces the annotation's config.resolved.yaml; only `quality` and `views` matter.
  AddConfigFlags(command, &flags->config, QualityOptionSchema());
  command->add_flag("--quiet", flags->quiet, "Only the verdict line (and errors) on stderr");
  command->callback([flags, exit_code] { *exit_code = RunReport(*flags); });
}

}  // namespace bcot::tools
