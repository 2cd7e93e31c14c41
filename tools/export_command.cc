// bcot export --sequence SEQ --annotation ANN --out ROOT [--config configs/export.yaml]
//             [--set key=value]... [--overwrite]
// Writes an annotated sequence in the BCOT release layout (see exporter.h).
#include <cstdio>
#include <memory>
#include <string>

#include "bcot/export/exporter.h"
#include "commands.h"

namespace bcot::tools {
namespace {

struct ExportFlags {
  ConfigFlags config;
  std::string sequence_dir;
  std::string annotation_dir;
  std::string out_root;
  bool overwrite = false;
};

int RunExport(const ExportFlags& flags) {
  StatusOr<ExportOptions> options =
      ReadExportOptions(flags.config.config_path, flags.config.overrides);
  if (!options.ok()) {
    PrintError("export", options.status().message());
    return options.status().ExitCode();
  }
  if (flags.overwrite) options->overwrite = true;
  const StatusOr<ExportSummary> summary =
      ExportToBcot(flags.sequence_dir, flags.annotation_dir, flags.out_root, *options);
  if (!summary.ok()) {
    PrintError("export", summary.status().message());
    return summary.status().ExitCode();
  }
  for (const std::string& scene : summary->scene_dirs) {
    std::fprintf(stderr, "bcot export: %s: %d frames, %dx%d%s\n", scene.c_str(),
                 summary->frames_per_camera, summary->width, summary->height,
                 summary->undistorted ? " (undistorted)" : "");
  }
  std::fprintf(stderr, "bcot export: model %s\n", summary->model_path.c_str());
  return 0;
}

}  // namespace

void AddExportCommand(CLI::App& app, int* exit_code) {
  auto flags = std::make_shared<ExportFlags>();
  CLI::App* command = app.add_subcommand(
      "export", "Write an annotated sequence in the BCOT release layout (K.txt, pose.txt, frames)");
  AddConfigFlags(command, &flags->config, ExportOptionSchema());
  command->add_option("--sequence", flags->sequence_dir, "Sequence directory (rig.yaml, frames)")
      ->required();
  command
      ->add_option("--annotation", flags->annotation_dir,
                   "Annotation directory of the sequence (<camera>/pose.txt or "
                   "rig_from_object.txt)")
      ->required();
  command->add_option("--out", flags->out_root, "Root of the release tree")->required();
  command->add_flag("--overwrite", flags->overwrite,
                    "Replace an existing <scene>/<Object> folder (same as --set overwrite=true)");
  command->callback([flags, exit_code] { *exit_code = RunExport(*flags); });
}

}  // namespace bcot::tools
