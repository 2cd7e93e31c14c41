// bcot eval --data ROOT (--results DIR | --online) [--out DIR] [--config configs/eval.yaml]
//           [--set key=value]... [--tracker-config configs/track.yaml] [--tracker-set k=v]...
// Scores monocular tracking on a BCOT-layout (or RBOT) benchmark; see evaluator.h. Online, the
// tracker is bcot's own region tracker (region_monocular_tracker.h) configured like `bcot
// annotate` (only its solver, colour and tracker sections apply; views are ignored).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "bcot/annotate/annotate_options.h"
#include "bcot/core/file_util.h"
#include "bcot/eval/eval_report.h"
#include "bcot/eval/evaluator.h"
#include "bcot/eval/online/region_monocular_tracker.h"
#include "commands.h"

namespace bcot::tools {
namespace {

struct EvalFlags {
  ConfigFlags config;
  ConfigFlags tracker_config;
  std::string data_root;
  std::string results_root;
  bool online = false;
  std::string out_dir;
  bool quiet = false;
};

int RunEval(const EvalFlags& flags) {
  if (flags.online == !flags.results_root.empty()) {
    PrintError("eval", "give exactly one of --results DIR (offline) and --online");
    return 2;
  }
  StatusOr<EvalOptions> options = ReadEvalOptions(flags.config.config_path, flags.config.overrides);
  if (!options.ok()) {
    PrintError("eval", options.status().message());
    return options.status().ExitCode();
  }
  MonocularTrackerFactory factory;
  if (flags.online) {
    const StatusOr<AnnotateOptions> tracker_options =
        ReadAnnotateOptions(flags.tracker_config.config_path, flags.tracker_config.overrides);
    if (!tracker_options.ok()) {
      PrintError("eval", tracker_options.status().message());
      return tracker_options.status().ExitCode();
    }
    factory = MakeRegionTrackerFactory(tracker_options->tracker);
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
    results = EvaluateOnline(
        *sequences, factory, *options, poses_root,
        [quiet = flags.quiet](int done, int total, const SequenceResult& result) {
          if (quiet) return;
          std::fprintf(stderr, "bcot eval: %d/%d %s/%s: %d resets\n", done, total,
                       result.scene.c_str(), result.object.c_str(), result.num_resets);
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

void AddEvalCommand(CLI::App& app, int* exit_code) {
  auto flags = std::make_shared<EvalFlags>();
  CLI::App* command = app.add_subcommand(
      "eval",
      "Score monocular 6DoF tracking on a BCOT (or RBOT) benchmark (paper Table 6); the "
      "Markdown table goes to stdout");
  AddConfigFlags(command, &flags->config, EvalOptionSchema());
  command->add_option("--data", flags->data_root, "Benchmark root (BCOT release or RBOT layout)")
      ->required();
  command->add_option("--results", flags->results_root,
                      "Offline: tracker poses as <DIR>/<scene>/<Object>/pose.txt (cam_from_object "
                      "per frame, frames 0..N-1 or 1..N-1)");
  command->add_flag("--quiet", flags->quiet, "No per-sequence progress on stderr");
  command->add_flag("--online", flags->online,
                    "Run bcot's tracker with the protocol (GT start, reset after a 5deg/5cm loss)");
  command->add_option("--tracker-config", flags->tracker_config.config_path,
                      "Online: tracker options, as for bcot annotate (e.g. configs/track.yaml; "
                      "default: the built-in annotation defaults)");
  command->add_option("--tracker-set", flags->tracker_config.overrides,
                      "Online: override of the tracker config, section.key=value (repeatable)");
  command->add_option("--out", flags->out_dir,
                      "Write eval.md, eval.csv, eval.json, add_curve.svg (and poses/ online) here");
  command->callback([flags, exit_code] { *exit_code = RunEval(*flags); });
}

}  // namespace bcot::tools
