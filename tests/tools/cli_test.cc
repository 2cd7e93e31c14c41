// The `bcot` dispatcher: help, version and usage errors with the documented exit codes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "bcot/core/version.h"
#include "test_util.h"

namespace bcot {
namespace {

using test::BcotBinary;
using test::RunCommand;
using ::testing::HasSubstr;

TEST(CliTest, HelpListsSubcommandsAndExitsZero) {
  std::string output;
  EXPECT_EQ(RunCommand(BcotBinary() + " --help", &output), 0);
  EXPECT_THAT(output, HasSubstr("synth"));
}

TEST(CliTest, VersionExitsZero) {
  std::string output;
  EXPECT_EQ(RunCommand(BcotBinary() + " --version", &output), 0);
  EXPECT_THAT(output, HasSubstr(BcotVersion()));
}

TEST(CliTest, HelpCommandShowsTheCommandListOrOneCommand) {
  std::string output;
  EXPECT_EQ(RunCommand(BcotBinary() + " help", &output), 0);
  EXPECT_THAT(output, HasSubstr("annotate"));
  EXPECT_THAT(output, HasSubstr("Exit codes"));
  EXPECT_EQ(RunCommand(BcotBinary() + " help annotate", &output), 0);
  EXPECT_THAT(output, HasSubstr("--out"));
  EXPECT_THAT(output, HasSubstr("edge.enabled"));  // the options footer
}

TEST(CliTest, UnknownCommandIsNamedWithTheCommandList) {
  std::string output;
  EXPECT_EQ(RunCommand(BcotBinary() + " annotat seq", &output), 2);
  EXPECT_THAT(output, HasSubstr("unknown command 'annotat'"));
  EXPECT_THAT(output, HasSubstr("synth, export"));
  EXPECT_EQ(RunCommand(BcotBinary() + " help no-such-command", &output), 2);
  EXPECT_THAT(output, HasSubstr("unknown command 'no-such-command'"));
  EXPECT_EQ(RunCommand(BcotBinary(), &output), 2);
  EXPECT_THAT(output, HasSubstr("a command is required"));
}

TEST(CliTest, EveryCommandTakesQuiet) {
  for (const char* command : {"synth", "export", "eval", "calibrate", "capture", "init", "annotate",
                              "batch", "report", "review"}) {
    std::string output;
    EXPECT_EQ(RunCommand(BcotBinary() + " help " + command, &output), 0) << command;
    EXPECT_THAT(output, HasSubstr("--quiet")) << command;
  }
}

// `bcot review --frame N` must name a frame of the sequence: checked before the server starts.
TEST(CliTest, ReviewFrameOutsideTheSequenceExitsTwo) {
  test::TempDir dir;
  test::MakeTinyAnnotatedSequence(dir.File("seq"), 3, "");
  std::string output;
  EXPECT_EQ(
      RunCommand(BcotBinary() + " review " + dir.File("seq") + " --port 0 --frame 3", &output), 2);
  EXPECT_THAT(output, HasSubstr("--frame 3: the sequence has frames 0..2"));
  EXPECT_EQ(RunCommand(BcotBinary() + " review " + dir.File("seq") + " --frame -1", &output), 2);
}

TEST(CliTest, UsageErrorsExitTwo) {
  std::string output;
  EXPECT_EQ(RunCommand(BcotBinary(), &output), 2);
  EXPECT_EQ(RunCommand(BcotBinary() + " no-such-command", &output), 2);
  EXPECT_EQ(RunCommand(BcotBinary() + " --no-such-flag", &output), 2);
}

}  // namespace
}  // namespace bcot
