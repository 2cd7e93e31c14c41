#include "bcot/eval/bcot_layout.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "benchmark_test_data.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

TEST(BcotLayoutTest, ReadsEverySpellingOfK) {
  for (const std::string& text : {
           std::string("Matx33f K = Matx33f(481.34025, 0.0, 329.4003, 0.0, 481.8243, 260.3788, "
                       "0.000000, 0.000000, 1.000000);\n"),
           std::string("Matx33f(481.34025,0,329.4003, 0,481.8243,260.3788, 0,0,1)"),
           std::string("481.34025 0 329.4003\r\n0 481.8243 260.3788\r\n0 0 1\r\n"),
           std::string("481.34025f, 0.f, 329.4003f,\n0, 481.8243, 260.3788,\n0, 0, 1"),
       }) {
    const StatusOr<Camera> camera = ParseBcotIntrinsics(text, "K.txt");
    ASSERT_TRUE(camera.ok()) << camera.status().message() << "\n" << text;
    EXPECT_EQ(camera->fx, 481.34025);
    EXPECT_EQ(camera->fy, 481.8243);
    EXPECT_EQ(camera->cx, 329.4003);
    EXPECT_EQ(camera->cy, 260.3788);
  }
}

TEST(BcotLayoutTest, WrittenKReadsBackExactly) {
  Camera camera("c", 640, 512, 481.34025000000001, 481.8243, 329.40030000000002, 260.3788);
  camera = camera.Scaled(0.5);
  const StatusOr<Camera> read = ParseBcotIntrinsics(FormatBcotIntrinsics(camera), "K.txt");
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(read->fx, camera.fx);
  EXPECT_EQ(read->fy, camera.fy);
  EXPECT_EQ(read->cx, camera.cx);
  EXPECT_EQ(read->cy, camera.cy);
  EXPECT_THAT(FormatBcotIntrinsics(camera), ::testing::StartsWith("Matx33f K = Matx33f("));
}

TEST(BcotLayoutTest, BadKNamesFileAndLine) {
  StatusOr<Camera> camera = ParseBcotIntrinsics("500 0 320\n0 500 256\n0 0\n", "K.txt");
  EXPECT_EQ(camera.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(camera.status().message(), HasSubstr("K.txt:3"));
  EXPECT_THAT(camera.status().message(), HasSubstr("got 8"));
  camera = ParseBcotIntrinsics("500 0 320\n0 x 256\n0 0 1\n", "K.txt");
  EXPECT_THAT(camera.status().message(), HasSubstr("K.txt:2"));
  EXPECT_THAT(camera.status().message(), HasSubstr("'x'"));
  camera = ParseBcotIntrinsics("Matx33f(500, 1, 320, 0, -500, 256, 0, 0, 2)", "K.txt");
  EXPECT_THAT(camera.status().message(), HasSubstr("fy = -500"));
  EXPECT_THAT(camera.status().message(), HasSubstr("entry 2 = 1"));
  EXPECT_THAT(camera.status().message(), HasSubstr("entry 9 = 2"));
  camera = ParseBcotIntrinsics("Matx33f K = Matx33f(500, 0, 320,", "K.txt");
  EXPECT_THAT(camera.status().message(), HasSubstr("never closed"));
}

TEST(BcotLayoutTest, LoadsATreeWithSpacesInNamesSorted) {
  test::TempDir dir;
  const auto gt = test::MakeTrajectory(3);
  test::WriteBcotSequence(dir.path(), "scene B", "3D Touch", gt);
  test::WriteBcotSequence(dir.path(), "scene A", "3D Touch", gt);
  test::WriteBcotSequence(dir.path(), "scene A", "Cat", gt);
  const StatusOr<std::vector<BenchmarkSequence>> sequences = LoadBcotDataset(dir.path());
  ASSERT_TRUE(sequences.ok()) << sequences.status().message();
  ASSERT_EQ(sequences->size(), 3u);
  EXPECT_EQ((*sequences)[0].RelativeDir(), "scene A/3D Touch");
  EXPECT_EQ((*sequences)[1].RelativeDir(), "scene A/Cat");
  EXPECT_EQ((*sequences)[2].RelativeDir(), "scene B/3D Touch");
  const BenchmarkSequence& s = (*sequences)[0];
  EXPECT_EQ(s.mesh_path, dir.File("models/3D Touch.obj"));
  EXPECT_EQ(s.camera.fx, 500.5);
  ASSERT_EQ(s.image_paths.size(), 3u);
  ASSERT_EQ(s.gt_cam_from_object.size(), 3u);
  // Six decimals in the file: equal to the trajectory within the printed precision.
  EXPECT_THAT(s.gt_cam_from_object[2], test::PoseNear(gt[2], 1e-4, 1e-3));
}

TEST(BcotLayoutTest, InconsistentTreesAreErrorsNamingTheFile) {
  test::TempDir dir;
  test::WriteBcotSequence(dir.path(), "s", "Cat", test::MakeTrajectory(3));
  test::WriteText(dir.File("s/Cat/pose.txt"), test::BcotPoseText(test::MakeTrajectory(2)));
  StatusOr<std::vector<BenchmarkSequence>> sequences = LoadBcotDataset(dir.path());
  EXPECT_EQ(sequences.status().code(), StatusCode::kInvalidInput);
  EXPECT_THAT(sequences.status().message(), HasSubstr("s/Cat/pose.txt: 2 poses for 3 frames"));

  test::WriteText(dir.File("s/Cat/pose.txt"), "1 0 0 0 1 0 0 0 1 0 0\n");
  sequences = LoadBcotDataset(dir.path());
  EXPECT_THAT(sequences.status().message(), HasSubstr("s/Cat/pose.txt:1"));

  std::filesystem::remove(dir.File("models/Cat.obj"));
  test::WriteText(dir.File("s/Cat/pose.txt"), test::BcotPoseText(test::MakeTrajectory(3)));
  sequences = LoadBcotDataset(dir.path());
  EXPECT_EQ(sequences.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(sequences.status().message(), HasSubstr("models/Cat.obj"));
}

TEST(BcotLayoutTest, ReadsTheRealCatRelease) {
  const std::string root = test::SharedDataPath("bcot_real_cat");
  if (root.empty() || !std::filesystem::exists(root)) GTEST_SKIP() << "no shared data";
  const StatusOr<std::vector<BenchmarkSequence>> sequences = LoadBcotDataset(root);
  ASSERT_TRUE(sequences.ok()) << sequences.status().message();
  ASSERT_EQ(sequences->size(), 1u);
  EXPECT_EQ((*sequences)[0].RelativeDir(), "handheld_demo/Cat");
  EXPECT_EQ((*sequences)[0].gt_cam_from_object.size(), 31u);
  EXPECT_EQ((*sequences)[0].camera.fx, 481.34025);
  EXPECT_EQ((*sequences)[0].camera.cy, 260.3788);
}

}  // namespace
}  // namespace bcot
