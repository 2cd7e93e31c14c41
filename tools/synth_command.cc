// bcot synth --config configs/synth/demo.yaml --out DIR [--set section.key=value]...
// Writes a synthetic multi-view sequence with exact ground truth (see synthesizer.h).
#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "bcot/synth/synth_options.h"
#include "bcot/synth/synthesizer.h"
#include "commands.h"

namespace bcot::tools {
namespace {

struct SynthFlags {
  ConfigFlags config;
  std::string out_dir;
  bool overwrite = false;
  bool quiet = false;
};

int RunSynth(const SynthFlags& flags) {
  StatusOr<SynthOptions> options =
      ReadSynthOptions(flags.config.config_path, flags.config.overrides);
  if (!options.ok()) {
    PrintError("synth", options.status().message());
    return options.status().ExitCode();
  }
  namespace fs = std::filesystem;
  std::error_code error;
  if (flags.overwrite && fs::exists(flags.out_dir, error) && !fs::is_empty(flags.out_dir, error)) {
    // Only ever delete what an earlier `bcot synth` wrote.
    if (!fs::exists(flags.out_dir + "/synth.resolved.yaml", error)) {
      PrintError("synth",
                 flags.out_dir +
                     ": --overwrite refused: not a bcot synth output (no synth.resolved.yaml)");
      return 2;
    }
    fs::remove_all(flags.out_dir, error);
    if (error) {
      PrintError("synth", flags.out_dir + ": cannot remove: " + error.message());
      return 1;
    }
  }
  const auto start = std::chrono::steady_clock::now();
  SynthProgress progress;
  if (!flags.quiet) {
    progress = [](int done, int total) {
      if (done == total || done % 10 == 0)
        std::fprintf(stderr, "bcot synth: frame %d/%d\n", done, total);
    };
  }
  const Status status = Synthesize(*options, flags.out_dir, progress);
  if (!status.ok()) {
    PrintError("synth", status.message());
    return status.ExitCode();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int num_cameras = 1 + static_cast<int>(options->cameras.arc_angles_deg.size() +
                                               options->cameras.cone_angles_deg.size());
  std::fprintf(stderr, "bcot synth: wrote %d frames x %d cameras (%dx%d) to %s in %.1f s\n",
               options->motion.num_frames, num_cameras, options->cameras.width,
               options->cameras.height, flags.out_dir.c_str(), seconds);
  return 0;
}

}  // namespace

void AddSynthCommand(CLI::App& app, int* exit_code) {
  auto flags = std::make_shared<SynthFlags>();
  CLI::App* command =
      app.add_subcommand("synth", "Render a synthetic multi-view sequence with exact ground truth");
  AddConfigFlags(command, &flags->config, SynthOptionSchema());
  command->add_option("--out", flags->out_dir, "Output sequence directory (new or empty)")
      ->required();
  command->add_flag("--overwrite", flags->overwrite,
                    "Replace an earlier bcot synth output in --out");
  command->add_flag("--quiet", flags->quiet, "No progress on stderr");
  command->callback([flags, exit_code] { *exit_code = RunSynth(*flags); });
}

}  // namespace bcot::tools
