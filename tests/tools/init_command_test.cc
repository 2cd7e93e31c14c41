// `bcot init` end to end: from a synthetic binocular sequence without init_pose.txt, clicks near
// the object's projected centre give a pose near the ground truth that `bcot annotate` accepts;
// bad clicks and an existing output are one-line errors naming the flag or the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "bcot/core/pose_io.h"
#include "bcot/core/sequence.h"
#include "bcot/core/status.h"
#include "bcot/render/mesh.h"
#include "synth_truth.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

// A 3-frame 320×256 binocular (90°) sequence made once by `bcot synth`, init_pose.txt removed.
class InitCommandTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    test::Synthesize(dir_->File("seq"),
                     "--set cameras.width=320 --set cameras.height=256 --set motion.num_frames=3"
                     " --set distractors.count=1 --set render.object_samples_per_axis=2");
    std::filesystem::remove(dir_->File("seq/init_pose.txt"));
  }
  static void TearDownTestSuite() { delete dir_; }

  static std::string CopySequence(const test::TempDir& into) {
    return test::CopyTree(dir_->File("seq"), into.File("seq"));
  }
  static std::string Init(const std::string& arguments) {
    return test::BcotBinary() + " init " + arguments;
  }
  static Eigen::Isometry3d TruthAtFrame0() { return test::TruePose(dir_->File("seq"), 0); }
  // `--click CAM:X,Y` at the true projected object centre of frame 0 plus `offset_px`.
  static std::string TrueClick(int camera_index, const Eigen::Vector2d& offset_px) {
    const Eigen::Vector2d pixel =
        test::TrueCentrePixel(dir_->File("seq"), camera_index, 0) + offset_px;
    return " --click cam" + std::to_string(camera_index) + ":" + std::to_string(pixel.x()) + "," +
           std::to_string(pixel.y());
  }

  static test::TempDir* dir_;
};

test::TempDir* InitCommandTest::dir_ = nullptr;

TEST_F(InitCommandTest, TwoClicksFindThePoseAndAnnotateAcceptsIt) {
  test::TempDir work;
  const std::string seq = CopySequence(work);
  std::string output;
  ASSERT_EQ(test::RunCommand(Init(seq + TrueClick(0, {3.0, -2.0}) + TrueClick(1, {-3.0, 3.0}) +
                                  " --candidates 1"),
                             &output),
            0)
      << output;
  EXPECT_THAT(output, HasSubstr("from 2 clicks"));
  const StatusOr<std::vector<Eigen::Isometry3d>> found = ReadPoseFile(seq + "/init_pose.txt");
  ASSERT_TRUE(found.ok()) << found.status().message();
  ASSERT_EQ(found->size(), 1u);
  EXPECT_THAT(found->front(), test::PoseNear(TruthAtFrame0(), 5.0, 10.0));
  for (const char* file : {"init_pose_cam0.png", "init_pose_cam1.png", "init_pose.cand1.txt",
                           "init_pose.cand1_cam0.png"}) {
    EXPECT_TRUE(std::filesystem::exists(seq + "/" + file)) << file;
  }

  ASSERT_EQ(
      test::RunCommand(
          test::BcotBinary() + " annotate --quiet " + seq + " --out " + work.File("ann"), &output),
      0)
      << output;
  EXPECT_THAT(output, HasSubstr("quality accepted")) << output;
}

TEST_F(InitCommandTest, OneClickAtAGivenDistanceFindsThePose) {
  test::TempDir work;
  const std::string seq = CopySequence(work);
  StatusOr<Sequence> sequence = LoadSequence(seq, /*require_init_pose=*/false);
  ASSERT_TRUE(sequence.ok());
  StatusOr<Mesh> mesh = Mesh::Load(sequence->object.mesh_path, sequence->object.unit_to_mm);
  ASSERT_TRUE(mesh.ok());
  // cam0 is the rig frame: the distance of the centre from its camera centre.
  const double distance_mm = (TruthAtFrame0() * mesh->bbox_center()).norm();
  std::string output;
  ASSERT_EQ(test::RunCommand(Init(seq + TrueClick(0, {2.0, 2.0}) + " --distance-mm " +
                                  std::to_string(distance_mm) + " --out " + work.File("one.txt")),
                             &output),
            0)
      << output;
  const StatusOr<std::vector<Eigen::Isometry3d>> found = ReadPoseFile(work.File("one.txt"));
  ASSERT_TRUE(found.ok()) << found.status().message();
  EXPECT_THAT(found->front(), test::PoseNear(TruthAtFrame0(), 5.0, 10.0));
  EXPECT_TRUE(std::filesystem::exists(work.File("one_cam1.png")));
}

TEST_F(InitCommandTest, ExistingOutputIsRefusedWithoutOverwrite) {
  test::TempDir work;
  const std::string seq = CopySequence(work);
  test::WriteText(seq + "/init_pose.txt", "1 0 0 0 1 0 0 0 1 0 0 600\n");
  std::string output;
  EXPECT_EQ(test::RunCommand(Init(seq + TrueClick(0, {0, 0}) + TrueClick(1, {0, 0})), &output), 2);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr(seq + "/init_pose.txt exists"));
  EXPECT_THAT(output, HasSubstr("--overwrite"));
}

TEST_F(InitCommandTest, BadClicksAreOneLineErrorsNamingTheFlag) {
  const std::string seq = dir_->File("seq");
  const struct {
    std::string arguments;
    std::string expected;
  } cases[] = {
      {" --click cam9:10,10 --click cam0:10,10",
       "no camera 'cam9' in the rig (cameras: cam0, cam1)"},
      {" --click cam0:400,10", "outside cam0's 320x256 image"},
      {" --click cam0:-3,10", "outside cam0's 320x256 image"},
      {" --click cam0:12x40", "--click 'cam0:12x40': expected CAM:X,Y"},
      {" --click cam0", "--click 'cam0': expected CAM:X,Y"},
      {" --click cam0:1,2,3", "expected CAM:X,Y"},
      {" --click cam0:10,10 --click cam0:20,20", "clicked twice"},
      {" --click cam0:10,10 --click cam1:10,10 --distance-mm 500",
       "--distance-mm applies to a single"},
      {" --click cam0:10,10 --distance-mm -5", "--distance-mm -5"},
      {" --click cam0:10,10 --frame 3", "--frame 3: the sequence has frames 0..2"},
  };
  for (const auto& c : cases) {
    std::string output;
    EXPECT_EQ(test::RunCommand(Init(seq + c.arguments + " --out /nonexistent/x.txt"), &output), 2)
        << c.arguments << ": " << output;
    EXPECT_EQ(test::CountLines(output), 1) << output;
    EXPECT_THAT(output, HasSubstr(c.expected)) << c.arguments;
  }
}

// `bcot synth` of the demo scene (one distractor) with `settings` into work/seq, without
// init_pose.txt; returns the sequence directory.
std::string SynthesizeWithoutInitPose(const test::TempDir& work, const std::string& settings) {
  const std::string seq = work.File("seq");
  test::Synthesize(seq,
                   settings + " --set distractors.count=1 --set render.object_samples_per_axis=2");
  std::filesystem::remove(seq + "/init_pose.txt");
  return seq;
}

// Without --click the object is found by its motion: 12 frames in which it moves ~15 mm and 6°
// per frame (more than its size over the sequence) in front of a static scene.
TEST(InitWithoutClicksTest, FindsTheMovingObjectAndItsPose) {
  test::TempDir work;
  const std::string seq = SynthesizeWithoutInitPose(
      work,
      "--set cameras.width=320 --set cameras.height=256 --set motion.num_frames=12"
      " --set motion.translation_mm_per_frame=15 --set motion.rotation_deg_per_frame=6");
  std::string output;
  ASSERT_EQ(test::RunCommand(test::BcotBinary() + " init " + seq, &output), 0) << output;
  EXPECT_THAT(output, HasSubstr("moving object: cam0 region"));
  EXPECT_THAT(output, HasSubstr("clicks taken: --click cam0:"));
  EXPECT_THAT(output, HasSubstr("from 2 clicks"));
  const StatusOr<std::vector<Eigen::Isometry3d>> found = ReadPoseFile(seq + "/init_pose.txt");
  ASSERT_TRUE(found.ok()) << found.status().message();
  const StatusOr<std::vector<Eigen::Isometry3d>> truth =
      ReadPoseFile(seq + "/gt/rig_from_object.txt");
  ASSERT_TRUE(truth.ok()) << truth.status().message();
  EXPECT_THAT(found->front(), test::PoseNear(truth->front(), 5.0, 10.0));
}

// An object that never moves is not found: a one-line error that asks for --click.
TEST(InitWithoutClicksTest, AStillObjectAsksForAClick) {
  test::TempDir work;
  const std::string seq = SynthesizeWithoutInitPose(
      work,
      "--set cameras.width=160 --set cameras.height=128 --set motion.num_frames=4"
      " --set motion.translation_mm_per_frame=0 --set motion.rotation_deg_per_frame=0");
  std::string output;
  EXPECT_EQ(test::RunCommand(test::BcotBinary() + " init " + seq, &output), 1) << output;
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("no moving object found at frame 0"));
  EXPECT_THAT(output, HasSubstr("give --click CAM:X,Y"));
  EXPECT_FALSE(std::filesystem::exists(seq + "/init_pose.txt"));
}

TEST_F(InitCommandTest, BadSearchOptionIsAConfigError) {
  std::string output;
  EXPECT_EQ(
      test::RunCommand(Init(dir_->File("seq") + " --click cam0:10,10 --set init.grid_rotations=5"),
                       &output),
      2);
  EXPECT_EQ(test::CountLines(output), 1) << output;
  EXPECT_THAT(output, HasSubstr("init.grid_rotations = 5"));
}

}  // namespace
}  // namespace bcot
