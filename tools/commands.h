// The `bcot` subcommands. Each lives in its own <name>_command.cc, registers its CLI11
// subcommand and options here, and stores its exit code (0 ok, 1 runtime failure, 2 usage
// or config error) in `*exit_code` when it runs. A command's body is short: parse, load,
// call one library entry point, print the summary.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "bcot/core/option_schema.h"

namespace bcot::tools {

void AddSynthCommand(CLI::App& app, int* exit_code);
void AddExportCommand(CLI::App& app, int* exit_code);
void AddEvalCommand(CLI::App& app, int* exit_code);
void AddCalibrateCommand(CLI::App& app, int* exit_code);
void AddCaptureCommand(CLI::App& app, int* exit_code);
void AddAnnotateCommand(CLI::App& app, int* exit_code);
void AddBatchCommand(CLI::App& app, int* exit_code);
void AddReportCommand(CLI::App& app, int* exit_code);
void AddInitCommand(CLI::App& app, int* exit_code);
void AddReviewCommand(CLI::App& app, int* exit_code);

// Common flags of commands that read a YAML config: --config FILE, --set key=value (repeatable).
struct ConfigFlags {
  std::string config_path;
  std::vector<std::string> overrides;
};
// `set_example` ("section.key=value") is one override the command accepts; `options_help` (the
// schema's option list) becomes the help's footer.
void AddConfigFlags(CLI::App* command, ConfigFlags* flags, const std::string& set_example,
                    const std::string& options_help);
template <typename Options>
void AddConfigFlags(CLI::App* command, ConfigFlags* flags, const OptionSchema<Options>& schema) {
  AddConfigFlags(command, flags, schema.Example(), schema.Help());
}
// The footer of a command's --help listing its options (OptionSchema::Help()).
std::string OptionsFooter(const std::string& options_help);

// Prints "bcot <command>: error: <message>" on stderr (one line).
void PrintError(const std::string& command, const std::string& message);

}  // namespace bcot::tools
