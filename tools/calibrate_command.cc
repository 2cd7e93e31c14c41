// bcot calibrate --config configs/calibrate.yaml --out DIR [--images-dir DIR] [--set k=v]...
// Chessboard calibration of a rig: writes DIR/rig.yaml (input contract), a per-image report
// and the resolved options (see calibrator.h).
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "bcot/capture/calibrator.h"
#include "bcot/core/yaml_util.h"
#include "commands.h"

namespace bcot::tools {
namespace {

struct CalibrateFlags {
  ConfigFlags config;
  std::string images_dir;
  std::string out_dir;
  bool overwrite = false;
  bool quiet = false;
};

int RunCalibrate(const CalibrateFlags& flags) {
  std::vector<std::string> overrides = flags.config.overrides;
  if (!flags.images_dir.empty()) {
    // An absolute path, so it does not depend on the config file's folder.
    overrides.push_back("input.images_dir=" +
                        FormatYamlString(std::filesystem::absolute(flags.images_dir).string()));
  }
  StatusOr<CalibrationOptions> options =
      ReadCalibrationOptions(flags.config.config_path, overrides);
  if (!options.ok()) {
    PrintError("calibrate", options.status().message());
    return options.status().ExitCode();
  }
  // Checked before the (slow) board search: a calibration is replaced only when asked to.
  std::error_code error;
  if (!flags.overwrite && std::filesystem::exists(flags.out_dir + "/rig.yaml", error)) {
    PrintError("calibrate", flags.out_dir + "/rig.yaml exists; pass --overwrite to replace it");
    return 2;
  }
  CalibrationProgress progress;
  if (!flags.quiet) {
    progress = [](int done, int total) {
      if (done == total || done % 10 == 0) {
        std::fprintf(stderr, "bcot calibrate: searched %d/%d images\n", done, total);
      }
    };
  }
  const StatusOr<CalibrationResult> result = Calibrate(*options, progress);
  if (!result.ok()) {
    PrintError("calibrate", result.status().message());
    return result.status().ExitCode();
  }
  const Status written = WriteCalibration(*result, *options, flags.out_dir);
  if (!written.ok()) {
    PrintError("calibrate", written.message());
    return written.ExitCode();
  }
  std::fprintf(stderr, "%s", FormatCalibrationSummary(*result).c_str());
  std::fprintf(stderr, "bcot calibrate: wrote %s/rig.yaml and calibration_report.csv\n",
               flags.out_dir.c_str());
  return 0;
}

}  // namespace

void AddCalibrateCommand(CLI::App& app, int* exit_code) {
  auto flags = std::make_shared<CalibrateFlags>();
  CLI::App* command = app.add_subcommand(
      "calibrate", "Calibrate a camera rig (intrinsics and cam_from_rig) from chessboard images");
  AddConfigFlags(command, &flags->config, CalibrationOptionSchema());
  command->add_option("--images-dir", flags->images_dir,
                      "Folder of chessboard images (sets input.images_dir)");
  command
      ->add_option("--out", flags->out_dir,
                   "Output folder for rig.yaml, calibration_report.csv, "
                   "calibrate.resolved.yaml")
      ->required();
  command->add_flag("--overwrite", flags->overwrite,
                    "Replace the rig.yaml of an earlier calibration in --out");
  command->add_flag("--quiet", flags->quiet, "No progress on stderr");
  command->callback([flags, exit_code] { *exit_code = RunCalibrate(*flags); });
}

}  // namespace bcot::tools
