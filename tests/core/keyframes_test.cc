#include "bcot/core/keyframes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "bcot/core/pose_io.h"
#include "bcot/core/se3.h"
#include "test_util.h"

namespace bcot {
namespace {

using test::PoseNear;
using ::testing::HasSubstr;

constexpr char kIdentityPose[] = "1 0 0 0 1 0 0 0 1 10 20 500";

TEST(KeyframesTest, ReadsFramesInAnyOrderAndSkipsBlankLines) {
  test::TempDir dir;
  const Eigen::Isometry3d pose = ExpSE3((Vector6d() << 5, -3, 400, 0.2, -0.1, 0.3).finished());
  test::WriteText(dir.File("keyframes.txt"),
                  "7\t" + FormatPoseLine(pose) + "\n\n  2 " + kIdentityPose + "\r\n\n");
  const StatusOr<KeyframePoses> keyframes = ReadKeyframeFile(dir.File("keyframes.txt"), 10);
  ASSERT_TRUE(keyframes.ok()) << keyframes.status().message();
  ASSERT_EQ(keyframes->size(), 2u);
  EXPECT_EQ(keyframes->begin()->first, 2);
  EXPECT_NEAR(keyframes->at(2).translation().z(), 500.0, 0.0);
  EXPECT_THAT(keyframes->at(7), PoseNear(pose, 1e-9, 1e-9));
}

TEST(KeyframesTest, ErrorsNameFileAndLine) {
  const std::string path = "seq/keyframes.txt";
  const auto error = [&](const std::vector<std::string>& lines) {
    const StatusOr<KeyframePoses> keyframes = ParseKeyframeLines(lines, path, 10);
    EXPECT_FALSE(keyframes.ok());
    return keyframes.ok() ? std::string() : keyframes.status().message();
  };
  const std::string pose = kIdentityPose;
  EXPECT_THAT(error({"", "x " + pose}), HasSubstr("seq/keyframes.txt:2: frame index 'x'"));
  EXPECT_THAT(error({"1.5 " + pose}), HasSubstr("keyframes.txt:1: frame index '1.5'"));
  EXPECT_THAT(error({"10 " + pose}), HasSubstr("keyframes.txt:1: frame 10 is outside"));
  EXPECT_THAT(error({"-1 " + pose}), HasSubstr("keyframes.txt:1: frame -1 is outside"));
  EXPECT_THAT(error({"3 " + pose, "3 " + pose}),
              HasSubstr("keyframes.txt:2: frame 3 already has a keyframe on line 1"));
  EXPECT_THAT(error({"3"}), HasSubstr("keyframes.txt:1: expected 12 numbers"));
  EXPECT_THAT(error({"3 1 0 0 0 1 0 0 0 1 10 20"}), HasSubstr("expected 12 numbers"));
  EXPECT_THAT(error({"4 1 0 0 0 2 0 0 0 1 10 20 30"}), HasSubstr("keyframes.txt:1:"));
  EXPECT_THAT(error({"4 1 0 0 0 1 0 0 0 1 10 nan 30"}), HasSubstr("number 11 of 12"));
}

TEST(KeyframesTest, AMissingFileIsAnError) {
  test::TempDir dir;
  EXPECT_FALSE(ReadKeyframeFile(dir.File("none.txt"), 3).ok());
}

TEST(KeyframesTest, AnEmptyFileHasNoKeyframes) {
  const StatusOr<KeyframePoses> keyframes = ParseKeyframeLines({"", "  "}, "k.txt", 3);
  ASSERT_TRUE(keyframes.ok());
  EXPECT_TRUE(keyframes->empty());
}

}  // namespace
}  // namespace bcot
