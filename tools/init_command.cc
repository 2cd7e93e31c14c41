// bcot init SEQ [--frame N] [--click CAM:X,Y]... [--distance-mm D] [--out FILE] [--overwrite]
//               [--candidates K] [--config FILE] [--set key=value]...
// Finds the object's pose at one frame from clicks on its centre, or from its motion without
// clicks (bcot/annotate/initializer.h), and writes it as a pose file (default
// SEQ/init_pose.txt) with one overlay PNG per view.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bcot/annotate/initializer.h"
#include "commands.h"

namespace bcot::tools {
namespace {

struct InitFlags {
  ConfigFlags config;
  std::string sequence_dir;
  int frame = 0;
  std::vector<std::string> clicks;
  double distance_mm = 0.0;
  bool has_distance = false;
  std::string out_path;
  bool overwrite = false;
  int candidates = 0;
  bool quiet = false;
};

int RunInit(const InitFlags& flags) {
  StatusOr<InitOptions> options = ReadInitOptions(flags.config.config_path, flags.config.overrides);
  if (!options.ok()) {
    PrintError("init", options.status().message());
    return options.status().ExitCode();
  }
  InitRequest request;
  request.frame = flags.frame;
  if (flags.has_distance) request.distance_mm = flags.distance_mm;
  for (const std::string& text : flags.clicks) {
    StatusOr<ImageClick> click = ParseImageClick(text);
    if (!click.ok()) {
      PrintError("init", click.status().message());
      return click.status().ExitCode();
    }
    request.clicks.push_back(*click);
  }
  InitOutputs outputs;
  outputs.pose_path =
      flags.out_path.empty() ? flags.sequence_dir + "/init_pose.txt" : flags.out_path;
  outputs.num_candidates = flags.candidates;
  outputs.overwrite = flags.overwrite;
  const auto start = std::chrono::steady_clock::now();
  const StatusOr<InitResult> result =
      InitializeSequenceDir(flags.sequence_dir, request, *options, outputs);
  if (!result.ok()) {
    PrintError("init", result.status().message());
    return result.status().ExitCode();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!flags.quiet) std::fprintf(stderr, "bcot init: %s", FormatInitSummary(*result).c_str());
  std::string files;
  for (const std::string& path : result->pose_files) files += (files.empty() ? "" : ", ") + path;
  std::fprintf(stderr, "bcot init: wrote %s (frame %d, with overlays) in %.1f s\n", files.c_str(),
               flags.frame, seconds);
  if (static_cast<int>(result->pose_files.size()) < 1 + flags.candidates) {
    std::fprintf(stderr, "bcot init: only %zu distinct answer(s) for --candidates %d\n",
                 result->candidates.size(), flags.candidates);
  }
  return 0;
}

}  // namespace

void AddInitCommand(CLI::App& app, int* exit_code) {
  auto flags = std::make_shared<InitFlags>();
  CLI::App* command =
      app.add_subcommand("init",
                         "Find the object's pose at one frame from clicks on its centre (or from "
                         "its motion); writes init_pose.txt");
  command->add_option("sequence", flags->sequence_dir, "Sequence directory (holds rig.yaml)")
      ->required();
  command->add_option("--frame", flags->frame, "Frame to initialise")->capture_default_str();
  command->add_option("--click", flags->clicks,
                      "CAM:X,Y: the object's centre in camera CAM's image, pixel column X and "
                      "row Y (repeatable; two or more views are triangulated). Without any, the "
                      "object is found by its motion over the sequence (init.motion_*)");
  command
      ->add_option_function<double>(
          "--distance-mm",
          [flags](double value) {
            flags->distance_mm = value;
            flags->has_distance = true;
          },
          "With one --click: the object centre's distance from that camera (mm); without it "
          "the depth is searched")
      ->type_name("D");
  command->add_option("--out", flags->out_path, "Pose file to write (default SEQ/init_pose.txt)");
  command->add_flag("--overwrite", flags->overwrite, "Replace existing pose files");
  command->add_flag("--quiet", flags->quiet, "No candidate table on stderr, only what was written");
  command
      ->add_option("--candidates", flags->candidates,
                   "Also write the K best distinct poses to <out stem>.cand<k>.txt")
      ->check(CLI::NonNegativeNumber)
      ->type_name("K");
  AddConfigFlags(command, &flags->config, InitOptionSchema());
  command->callback([flags, exit_code] { *exit_code = RunInit(*flags); });
}

}  // namespace bcot::tools
