// `bcot synth` end to end: exit codes, one-line errors, and a tiny run that LoadSequence reads.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "bcot/core/sequence.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

std::string Synth(const std::string& arguments) {
  return test::BcotBinary() + " synth " + arguments;
}

TEST(SynthCommandTest, HelpExitsZero) {
  std::string output;
  EXPECT_EQ(test::RunCommand(Synth("--help"), &output), 0);
  EXPECT_THAT(output, HasSubstr("--config"));
  EXPECT_THAT(output, HasSubstr("--out"));
  EXPECT_THAT(output, HasSubstr("--set"));
}

TEST(SynthCommandTest, MissingOutIsAUsageError) {
  std::string output;
  EXPECT_EQ(
      test::RunCommand(Synth("--config " + test::SourcePath("configs/synth/demo.yaml")), &output),
      2)
      << output;
}

TEST(SynthCommandTest, BadConfigIsAOneLineConfigErrorNamingFileAndKey) {
  test::TempDir dir;
  const std::string config = dir.File("bad.yaml");
  test::WriteText(config, "motion:\n  num_frames: 3\n  speed: 4\n");
  std::string output;
  EXPECT_EQ(test::RunCommand(Synth("--config " + config + " --out " + dir.File("out")), &output),
            2);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("bad.yaml:3"));
  EXPECT_THAT(output, HasSubstr("speed"));
  EXPECT_FALSE(std::filesystem::exists(dir.File("out")));

  // Out-of-range override: also 2, naming the field.
  EXPECT_EQ(test::RunCommand(Synth("--config " + test::SourcePath("configs/synth/demo.yaml") +
                                   " --out " + dir.File("out") + " --set motion.fps=-1"),
                             &output),
            2);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("motion.fps = -1"));
}

TEST(SynthCommandTest, TinyRunWritesEveryContractFile) {
  test::TempDir dir;
  const std::string out = dir.File("seq");
  std::string output;
  const std::string command =
      Synth("--config " + test::SourcePath("configs/synth/demo.yaml") + " --out " + out +
            " --set cameras.width=160 --set cameras.height=128 --set motion.num_frames=3"
            " --set distractors.count=1 --set render.object_samples_per_axis=2");
  ASSERT_EQ(test::RunCommand(command, &output), 0) << output;
  for (const char* file :
       {"rig.yaml", "object.yaml", "model/bunny.obj", "init_pose.txt", "timestamps.csv",
        "synth.resolved.yaml", "gt/rig_from_object.txt", "gt/cam0/pose.txt", "gt/cam1/pose.txt",
        "cam0/000000.png", "cam0/000002.png", "cam1/000002.png"}) {
    EXPECT_TRUE(std::filesystem::exists(out + "/" + file)) << file;
  }
  const StatusOr<Sequence> sequence = LoadSequence(out);
  ASSERT_TRUE(sequence.ok()) << sequence.status().message();
  EXPECT_EQ(sequence->num_frames, 3);
  EXPECT_EQ(sequence->rig.size(), 2);
  EXPECT_EQ(sequence->rig[0].camera.width, 160);

  // A second run into the same directory needs --overwrite.
  EXPECT_EQ(test::RunCommand(command, &output), 2);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_EQ(test::RunCommand(command + " --overwrite --quiet", &output), 0) << output;
}

}  // namespace
}  // namespace bcot
