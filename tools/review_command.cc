// bcot review <sequence dir> [--annotation DIR] [--frame N] [--host ADDRESS] [--port P]
//             [--config FILE] [--set key=value]...
// Serves a local web page to inspect a sequence and its annotation: every view side by side with
// the annotated contour, the reprojection-error timeline, bad frames and solver diagnostics;
// edits, re-annotation of frames and the initial pose from clicks (docs/review.md). Runs until
// interrupted (Ctrl-C).
#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <string>

#include "bcot/annotate/initializer.h"
#include "bcot/review/review_options.h"
#include "bcot/review/review_server.h"
#include "bcot/review/review_session.h"
#include "commands.h"

namespace bcot::tools {
namespace {

struct ReviewFlags {
  ConfigFlags config;
  std::string sequence_dir;
  std::string annotation_dir;
  int frame = 0;
  ReviewOptions options;
  bool quiet = false;
};

int RunReview(const ReviewFlags& flags) {
  const Status valid = flags.options.Validate();
  if (!valid.ok()) {
    PrintError("review", valid.message());
    return 2;
  }
  const StatusOr<InitOptions> init_options =
      ReadInitOptions(flags.config.config_path, flags.config.overrides);
  if (!init_options.ok()) {
    PrintError("review", init_options.status().message());
    return init_options.status().ExitCode();
  }
  const StatusOr<std::unique_ptr<ReviewSession>> session =
      ReviewSession::Load(flags.sequence_dir, flags.annotation_dir, *init_options);
  if (!session.ok()) {
    PrintError("review", session.status().message());
    return session.status().ExitCode();
  }
  const int num_frames = (*session)->sequence().num_frames;
  if (flags.frame >= num_frames) {
    PrintError("review", fmt::format("--frame {}: the sequence has frames 0..{}", flags.frame,
                                     num_frames - 1));
    return 2;
  }
  ReviewServer server(**session, flags.options);
  const StatusOr<int> port = server.Bind();
  if (!port.ok()) {
    PrintError("review", port.status().message());
    return 1;
  }
  if (!flags.options.LoopbackOnly()) {
    std::fprintf(stderr, "bcot review: listening on %s: clients from other machines are answered\n",
                 flags.options.host.c_str());
  }
  // The URL alone on stdout (scripts read it); the hint on stderr.
  std::printf("%s#frame=%d\n", server.Url().c_str(), flags.frame);
  std::fflush(stdout);
  if (!flags.quiet) {
    std::fprintf(stderr, "bcot review: open the address above in a browser; Ctrl-C stops\n");
  }
  server.Listen();
  return 0;
}

}  // namespace

void AddReviewCommand(CLI::App& app, int* exit_code) {
  auto flags = std::make_shared<ReviewFlags>();
  CLI::App* command = app.add_subcommand(
      "review", "Serve a local web page to inspect a sequence and its annotation");
  command->add_option("sequence", flags->sequence_dir, "Sequence directory")
      ->required()
      ->check(CLI::ExistingDirectory);
  command->add_option("--annotation", flags->annotation_dir,
                      "Annotation directory of the sequence (output of `bcot annotate`); without "
                      "it the frames are shown without contour. A new or empty directory is "
                      "where the page's \"annotate\" writes one (with the --config options)");
  command
      ->add_option("--host", flags->options.host,
                   "Address to listen on; a non-loopback address (e.g. 0.0.0.0) also accepts "
                   "clients from other machines")
      ->capture_default_str();
  command->add_option("--frame", flags->frame, "Frame the page opens at (its address says it)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--port", flags->options.port, "TCP port (0: any free port)")
      ->capture_default_str();
  command->add_flag("--quiet", flags->quiet, "Only the address on stdout (and errors on stderr)");
  // The page's initial-pose search is bcot init's (an annotate config is a valid one).
  AddConfigFlags(command, &flags->config, InitOptionSchema());
  command->callback([flags, exit_code] { *exit_code = RunReview(*flags); });
}

}  // namespace bcot::tools
