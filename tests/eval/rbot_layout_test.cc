#include "bcot/eval/rbot_layout.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "bcot/core/pose_io.h"
#include "benchmark_test_data.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

constexpr char kHeader[] = "r11\tr12\tr13\tr21\tr22\tr23\tr31\tr32\tr33\tt1\tt2\tt3\n";

// The lines of an RBOT pose file below its header: one pose per line.
std::string PoseLines(const std::vector<Eigen::Isometry3d>& poses) {
  std::string lines;
  for (const Eigen::Isometry3d& pose : poses) lines += FormatPoseLine(pose) + "\n";
  return lines;
}

TEST(RbotLayoutTest, CalibrationWithAndWithoutHeader) {
  test::TempDir dir;
  test::WriteText(
      dir.File("a.txt"),
      "fx\tfy\tcx\tcy\tk1\tk2\tp1\tp2\n650.048\t647.183\t324.328\t257.323\t0\t0\t0\t0\n");
  test::WriteText(dir.File("b.txt"), "650.048 647.183 324.328 257.323\n");
  for (const char* name : {"a.txt", "b.txt"}) {
    const StatusOr<Camera> camera = ReadRbotCalibration(dir.File(name));
    ASSERT_TRUE(camera.ok()) << camera.status().message();
    EXPECT_EQ(camera->fx, 650.048);
    EXPECT_EQ(camera->fy, 647.183);
    EXPECT_EQ(camera->cx, 324.328);
    EXPECT_EQ(camera->cy, 257.323);
  }
  test::WriteText(dir.File("c.txt"), "fx fy cx cy\n650 647 324\n");
  EXPECT_THAT(ReadRbotCalibration(dir.File("c.txt")).status().message(), HasSubstr("c.txt:2"));
  test::WriteText(dir.File("d.txt"), "650 647 324 257 0.1\n");
  EXPECT_THAT(ReadRbotCalibration(dir.File("d.txt")).status().message(), HasSubstr("distortion"));
}

TEST(RbotLayoutTest, PosesWithAndWithoutHeaderAreTheSameAndErrorsCountTheHeaderLine) {
  test::TempDir dir;
  const auto poses = test::MakeTrajectory(4);
  const std::string body = PoseLines(poses);
  test::WriteText(dir.File("with.txt"), kHeader + body);
  test::WriteText(dir.File("without.txt"), body);
  const StatusOr<std::vector<Eigen::Isometry3d>> with = ReadRbotPoses(dir.File("with.txt"));
  const StatusOr<std::vector<Eigen::Isometry3d>> without = ReadRbotPoses(dir.File("without.txt"));
  ASSERT_TRUE(with.ok()) << with.status().message();
  ASSERT_TRUE(without.ok()) << without.status().message();
  ASSERT_EQ(with->size(), 4u);
  ASSERT_EQ(without->size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE((*with)[i].isApprox((*without)[i], 0.0));

  test::WriteText(dir.File("bad.txt"), std::string(kHeader) + FormatPoseLine(poses[0]) +
                                           "\n1 0 0 0 1 0 0 0 1 0 0 nan\n");
  const Status status = ReadRbotPoses(dir.File("bad.txt")).status();
  EXPECT_EQ(status.code(), StatusCode::kInvalidInput);
  EXPECT_THAT(status.message(), HasSubstr("bad.txt:3"));
}

TEST(RbotLayoutTest, LoadsBodiesOfOneVariant) {
  test::TempDir dir;
  test::WriteText(dir.File("poses_first.txt"), kHeader + PoseLines(test::MakeTrajectory(3)));
  test::WriteText(dir.File("camera_calibration.txt"), "fx\tfy\tcx\tcy\n650\t647\t324\t257\n");
  for (const char* name : {"squirrel", "ape"}) {
    test::WriteText(dir.File(std::string(name) + "/" + name + ".obj"), test::CubeObj());
    for (int f = 0; f < 3; ++f) {
      test::WriteFrameImage(fmt::format("{}/{}/frames/a_regular{:04d}.png", dir.path(), name, f),
                            f);
    }
  }
  test::WriteFrameImage(dir.File("ape/frames/b_dynamiclight0000.png"), 0);  // other variant
  const StatusOr<std::vector<BenchmarkSequence>> sequences =
      LoadRbotDataset(dir.path(), "a_regular", "poses_first.txt");
  ASSERT_TRUE(sequences.ok()) << sequences.status().message();
  ASSERT_EQ(sequences->size(), 2u);
  EXPECT_EQ((*sequences)[0].RelativeDir(), "a_regular/ape");
  EXPECT_EQ((*sequences)[1].RelativeDir(), "a_regular/squirrel");
  EXPECT_EQ((*sequences)[1].image_paths[2], dir.File("squirrel/frames/a_regular0002.png"));
  EXPECT_EQ((*sequences)[1].gt_cam_from_object.size(), 3u);
  EXPECT_EQ((*sequences)[0].camera.fy, 647.0);
  // b_dynamiclight has one frame for three poses.
  const Status status = LoadRbotDataset(dir.path(), "b_dynamiclight", "poses_first.txt").status();
  EXPECT_EQ(status.code(), StatusCode::kInvalidInput);
  EXPECT_THAT(status.message(), HasSubstr("b_dynamiclight0001.png"));
}

}  // namespace
}  // namespace bcot
