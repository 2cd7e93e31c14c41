// `bcot eval` end to end: exit codes, one-line errors, written outputs.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "eval/benchmark_test_data.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

std::string Bcot(const std::string& arguments) { return test::BcotBinary() + " " + arguments; }
std::string Quoted(const std::string& path) { return "'" + path + "'"; }

TEST(EvalCommandTest, OfflineWritesEveryReportAndPrintsTheTable) {
  test::TempDir dir;
  test::WriteBcotSequence(dir.File("data"), "scene A", "Cube Part", test::MakeTrajectory(5));
  std::string output;
  // GT against itself: the release tree doubles as a results tree.
  ASSERT_EQ(test::RunCommand(Bcot("eval --data " + Quoted(dir.File("data")) + " --results " +
                                  Quoted(dir.File("data")) + " --out " + Quoted(dir.File("out"))),
                             &output),
            0)
      << output;
  EXPECT_THAT(output, HasSubstr("| all | 100.0 | 100.0 | 100.0 | 100.0 | 100.0 | 100.0 | 100.0 | "
                                "100.0 | 100.0 | – | 100.0 | 4 | 0 |"));
  for (const char* name :
       {"eval.md", "eval.csv", "eval.json", "add_curve.svg", "eval.resolved.yaml"}) {
    EXPECT_TRUE(std::filesystem::exists(dir.File(std::string("out/") + name))) << name;
  }
}

TEST(EvalCommandTest, ErrorsAreOneLineWithTheRightExitCode) {
  test::TempDir dir;
  test::WriteBcotSequence(dir.File("data"), "s", "Cat", test::MakeTrajectory(3));
  std::string output;
  EXPECT_EQ(test::RunCommand(
                Bcot("eval --data " + dir.File("data") + " --online --tracker-set frame.rounds=0"),
                &output),
            2);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("frame.rounds"));

  test::WriteText(dir.File("results/s/Cat/pose.txt"), "1 0 0 0 1 0 0 0 1 0 0 0\n1 0 0 0 1 0\n");
  EXPECT_EQ(
      test::RunCommand(
          Bcot("eval --data " + dir.File("data") + " --results " + dir.File("results")), &output),
      1);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("results/s/Cat/pose.txt:2"));

  EXPECT_EQ(test::RunCommand(Bcot("eval --data " + dir.File("data") + " --results " +
                                  dir.File("results") + " --set layout=ycb"),
                             &output),
            2);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("layout = 'ycb'"));
  EXPECT_EQ(test::RunCommand(Bcot("eval --data " + dir.File("data")), &output), 2);
}

}  // namespace
}  // namespace bcot
