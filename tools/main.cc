// bcot: one binary, one subcommand per tool (like `colmap <command>`).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bcot/core/version.h"
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

namespace {

std::vector<const CLI::App*> Commands(const CLI::App& app) {
  std::vector<const CLI::App*> commands;
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
    commands.push_back(command);
  }
  return commands;
}

const CLI::App* FindCommand(const CLI::App& app, const std::string& name) {
  for (const CLI::App* command : Commands(app)) {
    if (command->get_name() == name) return command;
  }
  return nullptr;
}

std::string CommandNames(const CLI::App& app) {
  std::string names;
  for (const CLI::App* command : Commands(app)) {
    names += (names.empty() ? "" : ", ") + command->get_name();
  }
  return names;
}

}  // namespace

// `bcot help [command]`, a missing or an unknown command; the exit code when one of those
// applies (and was answered), else -1 (CLI11 parses the arguments).
int HandleHelpAndUnknownCommands(const CLI::App& app, int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "bcot: a command is required: %s (bcot help <command>)\n",
                 CommandNames(app).c_str());
    return 2;
  }
  const std::string first = argv[1];
  if (first == "help") {
    if (argc == 2) {
      std::printf("%s", app.help().c_str());
      return 0;
    }
    const CLI::App* command = FindCommand(app, argv[2]);
    if (command == nullptr) {
      std::fprintf(stderr, "bcot: unknown command '%s'; the commands are: %s\n", argv[2],
                   CommandNames(app).c_str());
      return 2;
    }
    std::printf("%s", command->help().c_str());
    return 0;
  }
  if (!first.empty() && first[0] != '-' && FindCommand(app, first) == nullptr) {
    std::fprintf(stderr, "bcot: unknown command '%s'; the commands are: %s\n", first.c_str(),
                 CommandNames(app).c_str());
    return 2;
  }
  return -1;
}

}  // namespace bcot::tools

int main(int argc, char** argv) {
  CLI::App app{"bcot: multi-view 6DoF pose annotation for textureless objects", "bcot"};
  app.set_version_flag("--version", bcot::BcotVersion());
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
  bcot::tools::AddReviewCommand(app, &exit_code);
  app.footer(
      "bcot help <command> (or bcot <command> --help) lists a command's options.\nExit codes: 0 "
      "success (annotation accepted), 1 failure, 2 usage or configuration error, 3 annotation "
      "written but rejected by the quality check (annotate, batch, report; export of a rejected "
      "annotation).");
  const int early = bcot::tools::HandleHelpAndUnknownCommands(app, argc, argv);
  if (early >= 0) return early;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);  // prints help/version or the usage error
    return code == 0 ? 0 : 2;
  }
  return exit_code;
}
