// `bcot eval` and `bcot export` end to end: exit codes, one-line errors, written outputs.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "bcot/core/pose_io.h"
#include "bcot/synth/synthesizer.h"
#include "eval/benchmark_test_data.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

std::string Bcot(const std::string& arguments) { return test::BcotBinary() + " " + arguments; }
int CountLines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}
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
  EXPECT_EQ(CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("frame.rounds"));

  test::WriteText(dir.File("results/s/Cat/pose.txt"), "1 0 0 0 1 0 0 0 1 0 0 0\n1 0 0 0 1 0\n");
  EXPECT_EQ(
      test::RunCommand(
          Bcot("eval --data " + dir.File("data") + " --results " + dir.File("results")), &output),
      1);
  EXPECT_EQ(CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("results/s/Cat/pose.txt:2"));

  EXPECT_EQ(test::RunCommand(Bcot("eval --data " + dir.File("data") + " --results " +
                                  dir.File("results") + " --set layout=ycb"),
                             &output),
            2);
  EXPECT_EQ(CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("layout = 'ycb'"));
  EXPECT_EQ(test::RunCommand(Bcot("eval --data " + dir.File("data")), &output), 2);
}

TEST(ExportCommandTest, ExportsASyntheticSequenceAndRejectsBadOptions) {
  test::TempDir dir;
  SynthOptions options;
  options.cameras.width = 160;
  options.cameras.height = 128;
  options.motion.num_frames = 3;
  options.distractors.count = 0;
  options.render.object_samples_per_axis = 1;
  options.render.background_samples_per_axis = 1;
  ASSERT_TRUE(Synthesize(options, dir.File("seq")).ok());
  std::string output;
  ASSERT_EQ(test::RunCommand(Bcot("export --sequence " + dir.File("seq") + " --annotation " +
                                  dir.File("seq/gt") + " --out " + dir.File("release") +
                                  " --config " + test::SourcePath("configs/export.yaml")),
                             &output),
            0)
      << output;
  EXPECT_TRUE(std::filesystem::exists(dir.File("release/models/knot.obj")));
  EXPECT_TRUE(std::filesystem::exists(dir.File("release/seq/K.txt")));
  EXPECT_TRUE(std::filesystem::exists(dir.File("release/seq/knot/0001.png")));  // frames 0, 2
  EXPECT_FALSE(std::filesystem::exists(dir.File("release/seq/knot/0002.png")));
  const StatusOr<std::vector<Eigen::Isometry3d>> poses =
      ReadPoseFile(dir.File("release/seq/knot/pose.txt"));
  ASSERT_TRUE(poses.ok());
  EXPECT_EQ(poses->size(), 2u);

  // Exporting again needs --overwrite.
  const std::string again = Bcot("export --sequence " + dir.File("seq") + " --annotation " +
                                 dir.File("seq/gt") + " --out " + dir.File("release"));
  EXPECT_EQ(test::RunCommand(again, &output), 2);
  EXPECT_EQ(CountLines(output), 1) << output;
  EXPECT_EQ(test::RunCommand(again + " --overwrite", &output), 0) << output;

  EXPECT_EQ(test::RunCommand(again + " --set image_scale=0.3", &output), 2);
  EXPECT_EQ(CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("image_scale = 0.3"));
}

}  // namespace
}  // namespace bcot
