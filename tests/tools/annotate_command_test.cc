// `bcot annotate` end to end: a tiny run, exit codes and one-line errors for bad inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "bcot/annotate/output_lock.h"
#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/core/status.h"
#include "bcot/core/version.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A 3-frame 160×128 binocular sequence made once by `bcot synth`.
class AnnotateCommandTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    test::Synthesize(dir_->File("seq"),
                     "--set cameras.width=160 --set cameras.height=128 --set motion.num_frames=3"
                     " --set distractors.count=1 --set render.object_samples_per_axis=2");
  }
  static void TearDownTestSuite() { delete dir_; }

  // A private copy of the sequence the test may break.
  static std::string CopySequence(const test::TempDir& into) {
    return test::CopyTree(dir_->File("seq"), into.File("seq"));
  }
  static std::string Annotate(const std::string& arguments) {
    return test::BcotBinary() + " annotate --quiet " + arguments;
  }

  static test::TempDir* dir_;
};

test::TempDir* AnnotateCommandTest::dir_ = nullptr;

TEST_F(AnnotateCommandTest, HelpExitsZero) {
  std::string output;
  EXPECT_EQ(test::RunCommand(test::BcotBinary() + " annotate --help", &output), 0);
  EXPECT_THAT(output, HasSubstr("--out"));
  EXPECT_THAT(output, HasSubstr("--set"));
}

TEST_F(AnnotateCommandTest, TrackingRunWritesTheOutputContract) {
  test::TempDir out;
  std::string output;
  ASSERT_EQ(test::RunCommand(Annotate(dir_->File("seq") + " --out " + out.File("ann") +
                                      " --config " + test::SourcePath("configs/track.yaml")),
                             &output),
            0)
      << output;
  for (const char* file : {"rig_from_object.txt", "cam0/pose.txt", "cam1/pose.txt",
                           "config.resolved.yaml", "frames.csv", "DONE"}) {
    EXPECT_TRUE(std::filesystem::exists(out.File("ann/") + file)) << file;
  }
}

// --out must be bcot's own: an earlier annotation is written over (rerun with another config),
// a directory with anything else in it is refused (exit 2, naming the directory and the
// entry) unless --overwrite, which leaves the foreign file alone; the sequence directory itself
// is always refused.
TEST_F(AnnotateCommandTest, OutMustBeAnAnnotationDirectoryUnlessOverwrite) {
  test::TempDir out;
  const std::string track = " --config " + test::SourcePath("configs/track.yaml");
  std::string output;
  // A new directory, then a rerun into the same one with a different config.
  ASSERT_EQ(
      test::RunCommand(Annotate(dir_->File("seq") + " --out " + out.File("ann") + track), &output),
      0)
      << output;
  ASSERT_EQ(test::RunCommand(Annotate(dir_->File("seq") + " --out " + out.File("ann") + track +
                                      " --set frame.rounds=2"),
                             &output),
            0)
      << output;
  // A foreign file at the top and one inside a camera folder.
  for (const std::string foreign : {"holiday.jpg", "cam1/notes.txt"}) {
    SCOPED_TRACE(foreign);
    const std::string dir = out.File("with_" + std::to_string(foreign.size()));
    std::filesystem::copy(out.File("ann"), dir, std::filesystem::copy_options::recursive);
    ASSERT_TRUE(WriteFileAtomic(dir + "/" + foreign, "mine\n").ok());
    EXPECT_EQ(test::RunCommand(Annotate(dir_->File("seq") + " --out " + dir + track), &output), 2);
    EXPECT_EQ(test::CountLines(output), 1) << output;
    EXPECT_THAT(output, HasSubstr(dir));
    EXPECT_THAT(output, HasSubstr("'" + foreign + "'"));
    EXPECT_THAT(output, HasSubstr("--overwrite"));
    EXPECT_EQ(test::RunCommand(
                  Annotate(dir_->File("seq") + " --out " + dir + track + " --overwrite"), &output),
              0)
        << output;
    EXPECT_TRUE(std::filesystem::exists(dir + "/DONE"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + foreign));
  }
  // The sequence directory, with or without --overwrite.
  for (const char* flag : {"", " --overwrite"}) {
    EXPECT_EQ(
        test::RunCommand(Annotate(dir_->File("seq") + " --out " + dir_->File("seq") + track + flag),
                         &output),
        2);
    EXPECT_THAT(output, HasSubstr("is the sequence directory"));
  }
  EXPECT_FALSE(std::filesystem::exists(dir_->File("seq/rig_from_object.txt")));
}

// A run into an annotation that another run is writing (its lock held) is refused at once, the
// other run's files untouched; once the lock is free, the run goes through.
TEST_F(AnnotateCommandTest, AnAnnotationBeingWrittenIsRefused) {
  test::TempDir out;
  const std::string run = Annotate(dir_->File("seq") + " --out " + out.File("ann") + " --config " +
                                   test::SourcePath("configs/track.yaml"));
  std::string output;
  ASSERT_EQ(test::RunCommand(run, &output), 0) << output;
  const StatusOr<std::string> poses = ReadTextFile(out.File("ann/rig_from_object.txt"));
  ASSERT_TRUE(poses.ok());
  {
    const StatusOr<OutputLock> held = OutputLock::Acquire(out.File("ann"));
    ASSERT_TRUE(held.ok()) << held.status().message();
    for (const std::string& extra : {std::string(), std::string(" --frames 1:2")}) {
      EXPECT_EQ(test::RunCommand(run + extra + " --set frame.rounds=2", &output), 1) << extra;
      EXPECT_EQ(test::CountLines(output), 1) << output;
      EXPECT_THAT(output, HasSubstr("another bcot run is writing this annotation"));
    }
    EXPECT_TRUE(std::filesystem::exists(out.File("ann/DONE")));
    EXPECT_EQ(*ReadTextFile(out.File("ann/rig_from_object.txt")), *poses);
  }
  EXPECT_EQ(test::RunCommand(run + " --set frame.rounds=2", &output), 0) << output;
}

// Progress into a pipe (a log): whole lines, no carriage returns. Every output header carries
// the version, the time and the config hash of DONE. `bcot report --config` measures with
// another file's quality options: a threshold no annotation meets is a rejection (exit 3).
TEST_F(AnnotateCommandTest, LogProgressProvenanceAndReportConfig) {
  test::TempDir out;
  std::string output;
  ASSERT_EQ(
      test::RunCommand(test::BcotBinary() + " annotate " + dir_->File("seq") + " --out " +
                           out.File("ann") + " --config " + test::SourcePath("configs/track.yaml"),
                       &output),
      0)
      << output;
  EXPECT_THAT(output, HasSubstr("bcot annotate: frame 3/3"));
  EXPECT_EQ(output.find('\r'), std::string::npos) << output;

  const std::string done = *ReadTextFile(out.File("ann/DONE"));
  const std::string hash_line = done.substr(done.find("config_hash: "));
  const std::string config_hash = hash_line.substr(13, hash_line.find('\n') - 13);
  ASSERT_FALSE(config_hash.empty());
  const nlohmann::json quality = nlohmann::json::parse(*ReadTextFile(out.File("ann/quality.json")));
  EXPECT_EQ(quality["bcot_version"], BcotVersion());
  EXPECT_EQ(quality["config_hash"], config_hash);
  EXPECT_THAT(quality["created_utc"].get<std::string>(),
              ::testing::MatchesRegex("[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z"));
  const std::string config = *ReadTextFile(out.File("ann/config.resolved.yaml"));
  EXPECT_THAT(config, HasSubstr("# bcot_version: " + std::string(BcotVersion())));
  EXPECT_THAT(config, HasSubstr("# config_hash: " + config_hash));
  EXPECT_THAT(config, HasSubstr("# created_utc: "));
  EXPECT_THAT(*ReadTextFile(out.File("ann/report.html")),
              HasSubstr("bcot " + std::string(BcotVersion())));

  test::WriteText(out.File("strict.yaml"), "quality:\n  threshold_px: 0.000001\n");
  EXPECT_EQ(test::RunCommand(test::BcotBinary() + " report --quiet " + out.File("ann") +
                                 " --config " + out.File("strict.yaml"),
                             &output),
            kExitRejected)
      << output;
  EXPECT_THAT(output, HasSubstr("rejected"));
  EXPECT_EQ(test::CountLines(output), 1) << output;  // --quiet: the verdict line only
  test::WriteText(out.File("typo.yaml"), "quality:\n  treshold_px: 1\n");
  EXPECT_EQ(test::RunCommand(test::BcotBinary() + " report " + out.File("ann") + " --config " +
                                 out.File("typo.yaml"),
                             &output),
            2)
      << output;
  EXPECT_THAT(output, HasSubstr("treshold_px"));
}

// --keyframes FILE in place of init_pose.txt, then --frames re-annotating a range of that
// annotation; a bad keyframes line is a one-line error naming file and line.
TEST_F(AnnotateCommandTest, KeyframesAndFrameRangeFromTheCommandLine) {
  test::TempDir dir;
  const std::string seq = CopySequence(dir);
  std::filesystem::remove(seq + "/init_pose.txt");
  const std::string config = " --config " + test::SourcePath("configs/track.yaml");
  std::string output;
  test::WriteText(dir.File("keys.txt"), "1 1 0 0 0 1 0 0 0 1 0 0\n");
  EXPECT_NE(test::RunCommand(Annotate(seq + " --out " + dir.File("ann") + config + " --keyframes " +
                                      dir.File("keys.txt")),
                             &output),
            0);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("keys.txt:1: expected 12 numbers"));

  const StatusOr<std::vector<Eigen::Isometry3d>> truth =
      ReadPoseFile(seq + "/gt/rig_from_object.txt");
  ASSERT_TRUE(truth.ok());
  test::WriteText(dir.File("keys.txt"), "1 " + FormatPoseLine((*truth)[1]) + "\n");
  ASSERT_EQ(test::RunCommand(Annotate(seq + " --out " + dir.File("ann") + config + " --keyframes " +
                                      dir.File("keys.txt")),
                             &output),
            0)
      << output;
  const std::string before = *ReadTextFile(dir.File("ann/rig_from_object.txt"));
  ASSERT_EQ(test::RunCommand(Annotate(seq + " --out " + dir.File("ann") + config + " --keyframes " +
                                      dir.File("keys.txt") + " --frames 2:2"),
                             &output),
            0)
      << output;
  EXPECT_TRUE(std::filesystem::exists(dir.File("ann/DONE")));
  const std::string after = *ReadTextFile(dir.File("ann/rig_from_object.txt"));
  // Frames 0 and 1 (before the range; 3 frames in all) are byte-identical.
  const auto first_two = [](const std::string& text) {
    return text.substr(0, text.find('\n', text.find('\n') + 1));
  };
  EXPECT_EQ(first_two(after), first_two(before));
  EXPECT_EQ(test::RunCommand(Annotate(seq + " --out " + dir.File("ann") + config + " --frames 2:7"),
                             &output),
            2);
  EXPECT_THAT(output, HasSubstr("--frames 2:7"));
}

// A white object lit beyond the sensor's full scale: its boundary shows only in saturated
// channels on most of its contour, and `bcot annotate` and `bcot report` say so, naming the
// cameras; the demo sequence gets no such note.
TEST_F(AnnotateCommandTest, ASaturatedObjectGetsANoteNamingTheCameras) {
  test::TempDir work;
  test::Synthesize(work.File("seq"),
                   "--set cameras.width=160 --set cameras.height=128 --set motion.num_frames=3"
                   " --set render.object_samples_per_axis=2 --set 'object.color_rgb=[250,250,250]'"
                   " --set sensor.exposure=4");
  const std::string track = " --config " + test::SourcePath("configs/track.yaml");
  std::string output;
  const int code =
      test::RunCommand(Annotate(work.File("seq") + " --out " + work.File("ann") + track), &output);
  EXPECT_TRUE(code == 0 || code == 3) << output;
  EXPECT_THAT(output, HasSubstr("bcot annotate: note: cam0: on "));
  EXPECT_THAT(output, HasSubstr("bcot annotate: note: cam1: on "));
  EXPECT_THAT(output, HasSubstr("saturated in every colour channel"));
  test::RunCommand(test::BcotBinary() + " report " + work.File("ann"), &output);
  EXPECT_THAT(output, HasSubstr("bcot report: note: cam0: on "));
  // --quiet: only the verdict line.
  test::RunCommand(test::BcotBinary() + " report --quiet " + work.File("ann"), &output);
  EXPECT_THAT(output, Not(HasSubstr("note:")));

  ASSERT_EQ(
      test::RunCommand(Annotate(dir_->File("seq") + " --out " + work.File("demo") + track), &output),
      0)
      << output;
  EXPECT_THAT(output, Not(HasSubstr("saturated")));
}

TEST_F(AnnotateCommandTest, BadConfigValueIsAConfigError) {
  test::TempDir out;
  std::string output;
  EXPECT_EQ(test::RunCommand(
                Annotate(dir_->File("seq") + " --out " + out.File("ann") + " --set frame.rounds=0"),
                &output),
            2);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("frame.rounds = 0"));
}

TEST_F(AnnotateCommandTest, BadInitPoseIsAOneLineErrorWithItsLine) {
  test::TempDir work;
  const std::string seq = CopySequence(work);
  test::WriteText(seq + "/init_pose.txt", "1 0 0 0 1 0 0 0 1 0 0\n");  // 11 numbers
  std::string output;
  EXPECT_EQ(test::RunCommand(Annotate(seq + " --out " + work.File("ann")), &output), 1);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("init_pose.txt"));
}

TEST_F(AnnotateCommandTest, MissingCameraFolderIsAOneLineError) {
  test::TempDir work;
  const std::string seq = CopySequence(work);
  std::filesystem::remove_all(seq + "/cam1");
  std::string output;
  const int code = test::RunCommand(Annotate(seq + " --out " + work.File("ann")), &output);
  EXPECT_TRUE(code == 1 || code == 2) << code;
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("cam1"));
}

TEST_F(AnnotateCommandTest, MeshThatDoesNotLoadIsAOneLineError) {
  test::TempDir work;
  const std::string seq = CopySequence(work);
  test::WriteText(seq + "/model/bunny.obj", "");
  std::string output;
  EXPECT_EQ(test::RunCommand(Annotate(seq + " --out " + work.File("ann")), &output), 1);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("bunny.obj"));
  EXPECT_FALSE(std::filesystem::exists(work.File("ann/DONE")));
}

TEST_F(AnnotateCommandTest, MissingSequenceIsAnError) {
  std::string output;
  const int code = test::RunCommand(Annotate("/nonexistent/seq --out /tmp/x"), &output);
  EXPECT_TRUE(code == 1 || code == 2) << code;
  EXPECT_EQ(test::CountLines(output), 1) << output;
}

}  // namespace
}  // namespace bcot
