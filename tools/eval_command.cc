// bcot eval --data ROOT (--results DIR | --online) [--out DIR] [--config configs/eval.yaml]
//           [--set key=value]...
// Scores monocular tracking on a BCOT-layout (or RBOT) benchmark; see evaluator.h.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "bcot/core/file_util.h"
#include "bcot/pipeline/eval_report.h"
#include "bcot/pipeline/evaluator.h"
#include "commands.h"

namespace bcot::tools {
namespace {

struct EvalFlags {
  ConfigFlags config;
  std::string data_root;
  std::string results_root;
  bool online = false;
  std::string out_dir;
};

int RunEval(const EvalFlags& flags, const MonocularTrackerFactory& factory) {
  if (flags.online == !flags.results_root.empty()) {
    PrintError("eval", "give exactly one of --results DIR (offline) and --online");
    return 2;
  }
  StatusOr<EvalOptions> options = ReadEvalOptions(flags.config.config_path, flags.config.overrides);
  if (!options.ok()) {
    PrintError("eval", options.status().message());
    return options.status().ExitCode();
  }
  if (flags.online && !factory) {
    PrintError("eval",
               "--online is not available yet: no monocular tracker is registered in this build; "
               "score a tracker's pose files with --results DIR instead");
    return 1;
  }
  const StatusOr<std::vector<BenchmarkSequence>> sequences =
      LoadBenchmark(flags.data_root, *options);
  if (!sequences.ok()) {
    PrintError("eval", sequences.status().message());
    return sequences.status().ExitCode();
  }
  StatusOr<std::vector<SequenceResult>> results = Status::Internal("not run");
  if (flags.online) {
    const std::string poses_root = flags.out_dir.empty() ? "" : flags.out_dir + "/poses";
    results = EvaluateOnline(*sequences, factory, *options, poses_root,
                             [](int done, int total, const SequenceResult& result) {
                               std::fprintf(stderr, "bcot eval: %d/%d %s/%s: %d resets\n", done,
                                            total, result.scene.c_str(), result.object.c_str(),
                                            result.num_resets);
                             });
  } else {
    results = EvaluateOffline(*sequences, flags.results_root, *options);
  }
  if (!results.ok()) {
    PrintError("eval", results.status().message());
    return results.status().ExitCode();
  }
  const EvalReport report =
      BuildEvalReport(*results, flags.online ? "online" : "offline", options->curve);
  if (!flags.out_dir.empty()) {
    Status status = WriteEvalReport(report, flags.out_dir);
    if (status.ok()) {
      status = WriteFileAtomic(flags.out_dir + "/eval.resolved.yaml", FormatEvalOptions(*options));
    }
    if (!status.ok()) {
      PrintError("eval", status.message());
      return status.ExitCode();
    }
  }
  std::fputs(FormatReportMarkdown(report).c_str(), stdout);
  return 0;
}

}  // namespace

void AddEvalCommand(CLI::App& app, int* exit_code, MonocularTrackerFactory tracker_factory) {
  auto flags = std::make_shared<EvalFlags>();
  CLI::App* command = app.add_subcommand(
      "eval", "Score monocular 6DoF tracking on a BCOT (or RBOT) benchmark (paper Table 6)");
  AddConfigFlags(command, &flags->config);
  command->add_option("--data", flags->data_root, "Benchmark root (BCOT release or RBOT layout)")
      ->required();
  command->add_option("--results", flags->results_root,
                      "Offline: tracker poses as <DIR>/<scene>/<Object>/pose.txt (cam_from_object "
                      "per frame, frames 0..N-1 or 1..N-1)");
  command->add_flag("--online", flags->online,
                    "Run bcot's tracker with the protocol (GT start, reset after a 5deg/5cm loss)");
  command->add_option("--out", flags->out_dir,
                      "Write eval.md, eval.csv, eval.json, add_curve.svg (and poses/ online) here");
  command->footer(
      "Options (YAML keys, --set key=value): layout (bcot|rbot), rbot_variant (a_regular), "
      "rbot_poses (poses_first.txt), reset_rotation_deg (5), reset_translation_mm (50), "
      "curve.max_fraction_of_d (0.1), curve.steps (100). The Markdown table goes to stdout.");
  command->callback(
      [flags, exit_code, tracker_factory] { *exit_code = RunEval(*flags, tracker_factory); });
}

}  // namespace bcot::tools
