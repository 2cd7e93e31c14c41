// bcot: one binary, one subcommand per tool (like `colmap <command>`).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>

#include "commands.h"

namespace bcot::tools {

void AddConfigFlags(CLI::App* command, ConfigFlags* flags, const std::string& set_example,
                    const std::string& options_help) {
  command->add_option("--config", flags->config_path, "YAML configuration file")
      ->check(CLI::ExistingFile);
  command->add_option("--set", flags->overrides,
                      fmt::format("Override one option, e.g. --set {} (repeatable)", set_example));
  if (!options_help.empty()) command->footer(OptionsFooter(options_help));
}

std::string OptionsFooter(const std::string& options_help) {
  return "Options (YAML keys of --config, or --set key=value): key = default [unit]  (rule) "
         "meaning\n" +
         options_help;
}

void PrintError(const std::string& command, const std::string& message) {
  std::fprintf(stderr, "bcot %s: error: %s\n", command.c_str(), message.c_str());
}

}  // namespace bcot::tools

int main(int argc, char** argv) {
  CLI::App app{"bcot: multi-view 6DoF pose annotation for textureless objects"};
  app.set_version_flag("--version", BCOT_VERSION);
  app.require_subcommand(1);
  int exit_code = 0;
  bcot::tools::AddSynthCommand(app, &exit_code);
  bcot::tools::AddExportCommand(app, &exit_code);
  bcot::tools::AddEvalCommand(app, &exit_code);
  bcot::tools::AddCalibrateCommand(app, &exit_code);
  bcot::tools::AddCaptureCommand(app, &exit_code);
  bcot::tools::AddInitCommand(app, &exit_code);
  bcot::tools::AddAnnotateCommand(app, &exit_code);
  bcot::tools::AddBatchCommand(app, &exit_code);
  bcot::tools::AddReportCommand(app, &exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);  // prints help/version or the usage error
    return code == 0 ? 0 : 2;
  }
  return exit_code;
}
