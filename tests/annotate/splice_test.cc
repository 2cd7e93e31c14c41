#include "bcot/annotate/splice.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "bcot/annotate/done_file.h"
#include "bcot/core/annotation_poses.h"
#include "bcot/core/file_util.h"
#include "bcot/core/pose_io.h"
#include "bcot/synth/synth_options.h"
#include "bcot/synth/synthesizer.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

// A binocular 6-frame sequence at 320×256, annotated once with the window on (size 3).
class SpliceTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    const StatusOr<SynthOptions> synth =
        ReadSynthOptions(test::SourcePath("configs/synth/demo.yaml"),
                         {"cameras.width=320", "cameras.height=256", "motion.num_frames=6"});
    BCOT_CHECK(synth.ok());
    BCOT_CHECK(Synthesize(*synth, dir_->File("seq")).ok());
    BCOT_CHECK(AnnotateSequenceDir(dir_->File("seq"), dir_->File("ann"), Options()).ok());
  }
  static void TearDownTestSuite() { delete dir_; }
  static AnnotateOptions Options() {
    AnnotateOptions options;
    options.window.enabled = true;
    options.window.size = 3;
    options.window.overlap = 1;
    return options;
  }
  // A fresh copy of the sequence and its annotation.
  static void Copy(const test::TempDir& to) {
    for (const char* name : {"seq", "ann"}) {
      std::filesystem::copy(dir_->File(name), to.File(name),
                            std::filesystem::copy_options::recursive);
    }
  }

  static test::TempDir* dir_;
};

test::TempDir* SpliceTest::dir_ = nullptr;

std::vector<std::string> Lines(const std::string& path) {
  const StatusOr<std::string> text = ReadTextFile(path);
  BCOT_CHECK(text.ok());
  return SplitLines(*text);
}

TEST(FrameRangeTest, ParsesAndRejects) {
  const StatusOr<FrameSpan> span = ParseFrameRange("2:4", 6);
  ASSERT_TRUE(span.ok());
  EXPECT_EQ(span->first, 2);
  EXPECT_EQ(span->end, 5);
  for (const char* bad : {"2", "a:3", "3:2", "0:6", "-1:2", ":"}) {
    const StatusOr<FrameSpan> error = ParseFrameRange(bad, 6);
    ASSERT_FALSE(error.ok()) << bad;
    EXPECT_THAT(error.status().message(), HasSubstr("--frames")) << bad;
  }
}

// A keyframe set at frame 3 and --frames 2:3: only lines 2 and 3 of rig_from_object.txt (and
// rows 2 and 3 of frames.csv) change; DONE, the derived files and the report are rewritten.
TEST_F(SpliceTest, ReplacesOnlyTheRangeAndRewritesDoneAndReport) {
  test::TempDir dir;
  Copy(dir);
  const std::vector<std::string> before = Lines(dir.File("ann/rig_from_object.txt"));
  const std::vector<std::string> csv_before = Lines(dir.File("ann/frames.csv"));
  std::filesystem::remove(dir.File("ann/quality.json"));
  const StatusOr<std::vector<Eigen::Isometry3d>> truth =
      ReadPoseFile(dir.File("seq/gt/rig_from_object.txt"));
  ASSERT_TRUE(truth.ok());
  test::WriteText(dir.File("seq/keyframes.txt"), "3 " + FormatPoseLine((*truth)[3]) + "\n");

  AnnotateInputs inputs;
  inputs.frames = "2:3";
  const StatusOr<AnnotationOutcome> outcome =
      AnnotateSequenceDir(dir.File("seq"), dir.File("ann"), Options(), inputs);
  ASSERT_TRUE(outcome.ok()) << outcome.status().message();
  EXPECT_EQ(outcome->frames, 6);

  const std::vector<std::string> after = Lines(dir.File("ann/rig_from_object.txt"));
  const std::vector<std::string> csv_after = Lines(dir.File("ann/frames.csv"));
  ASSERT_EQ(after.size(), before.size());
  ASSERT_EQ(csv_after.size(), csv_before.size());
  for (size_t f : {0u, 1u, 4u, 5u}) {
    EXPECT_EQ(after[f], before[f]) << "frame " << f;
    EXPECT_EQ(csv_after[1 + f], csv_before[1 + f]) << "frame " << f;
  }
  EXPECT_NE(after[3], before[3]);
  const StatusOr<std::vector<Eigen::Isometry3d>> poses = ReadAnnotationPoses(dir.File("ann"));
  ASSERT_TRUE(poses.ok());
  EXPECT_THAT((*poses)[3], test::PoseNear((*truth)[3], 0.5, 1.0));
  EXPECT_THAT((*poses)[2], test::PoseNear((*truth)[2], 0.5, 1.0));
  // The derived per-camera file follows rig_from_object.txt.
  const StatusOr<std::vector<Eigen::Isometry3d>> cam0 = ReadPoseFile(dir.File("ann/cam0/pose.txt"));
  StatusOr<Sequence> sequence = LoadSequence(dir.File("seq"));
  ASSERT_TRUE(cam0.ok() && sequence.ok());
  EXPECT_TRUE((*cam0)[3].isApprox(sequence->rig[0].cam_from_rig * (*poses)[3], 1e-12));
  EXPECT_TRUE(std::filesystem::exists(dir.File("ann/quality.json")));
  EXPECT_TRUE(std::filesystem::exists(dir.File("ann/report.html")));
  // DONE records the new input hash (the keyframe), so batch takes the annotation as current.
  const StatusOr<DoneRecord> done = ReadDoneFile(dir.File("ann"));
  ASSERT_TRUE(done.ok()) << done.status().message();
  EXPECT_EQ(done->input_hash, *SequenceInputHash(*sequence));
}

TEST_F(SpliceTest, NeedsAFinishedAnnotationWithTheSameOptions) {
  test::TempDir dir;
  Copy(dir);
  AnnotateInputs inputs;
  inputs.frames = "1:2";
  AnnotateOptions other = Options();
  other.tracker.frame.rounds = 1;
  const Status changed =
      AnnotateSequenceDir(dir.File("seq"), dir.File("ann"), other, inputs).status();
  EXPECT_EQ(changed.code(), StatusCode::kInvalidConfig);
  EXPECT_THAT(changed.message(), HasSubstr("other options"));
  EXPECT_TRUE(std::filesystem::exists(dir.File("ann/DONE")));
  inputs.frames = "1:9";
  EXPECT_EQ(
      AnnotateSequenceDir(dir.File("seq"), dir.File("ann"), Options(), inputs).status().code(),
      StatusCode::kInvalidConfig);
  ASSERT_TRUE(RemoveDoneFile(dir.File("ann")).ok());
  inputs.frames = "1:2";
  const Status unfinished =
      AnnotateSequenceDir(dir.File("seq"), dir.File("ann"), Options(), inputs).status();
  EXPECT_EQ(unfinished.code(), StatusCode::kNotFound);
  EXPECT_THAT(unfinished.message(), HasSubstr("DONE"));
}

}  // namespace
}  // namespace bcot
