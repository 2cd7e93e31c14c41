// The `bcot` dispatcher: help, version and usage errors with the documented exit codes.
#include <gtest/gtest.h>

#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;
using test::BcotBinary;
using test::RunCommand;

TEST(CliTest, HelpListsSubcommandsAndExitsZero) {
  std::string output;
  EXPECT_EQ(RunCommand(BcotBinary() + " --help", &output), 0);
  EXPECT_THAT(output, HasSubstr("synth"));
}

TEST(CliTest, VersionExitsZero) {
  std::string output;
  EXPECT_EQ(RunCommand(BcotBinary() + " --version", &output), 0);
  EXPECT_THAT(output, HasSubstr(BCOT_VERSION));
}

TEST(CliTest, UsageErrorsExitTwo) {
  std::string output;
  EXPECT_EQ(RunCommand(BcotBinary(), &output), 2);
  EXPECT_EQ(RunCommand(BcotBinary() + " no-such-command", &output), 2);
  EXPECT_EQ(RunCommand(BcotBinary() + " --no-such-flag", &output), 2);
}

}  // namespace
}  // namespace bcot
