#include "bcot/review/review_request.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bcot/core/camera.h"

namespace bcot {
namespace {

Rig TwoCameraRig() {
  Rig rig;
  rig.Add({Camera("left", 160, 128, 150.0, 150.0, 80.0, 64.0), Eigen::Isometry3d::Identity()});
  rig.Add({Camera("right", 160, 128, 150.0, 150.0, 80.0, 64.0), Eigen::Isometry3d::Identity()});
  return rig;
}

TEST(ParseFrameIndexTest, AcceptsIndicesInRange) {
  EXPECT_EQ(*ParseFrameIndex("0", 5), 0);
  EXPECT_EQ(*ParseFrameIndex("4", 5), 4);
  EXPECT_EQ(*ParseFrameIndex("004", 5), 4);
}

TEST(ParseFrameIndexTest, RejectsOutOfRangeAsNotFound) {
  const StatusOr<int> frame = ParseFrameIndex("5", 5);
  ASSERT_FALSE(frame.ok());
  EXPECT_EQ(frame.status().code(), StatusCode::kNotFound);
  EXPECT_NE(frame.status().message().find("0..4"), std::string::npos);
  EXPECT_FALSE(ParseFrameIndex("999999999", 5).ok());
  EXPECT_FALSE(ParseFrameIndex("0", 0).ok());
}

TEST(ParseFrameIndexTest, RejectsMalformedText) {
  const std::vector<std::string> texts = {"",
                                          "-1",
                                          "+1",
                                          " 1",
                                          "1 ",
                                          "1.0",
                                          "0x1",
                                          "1e3",
                                          "../0",
                                          "0/..",
                                          "%2e%2e",
                                          "1234567890",
                                          std::string("1\0", 2)};
  for (const std::string& text : texts) {
    const StatusOr<int> frame = ParseFrameIndex(text, 5);
    ASSERT_FALSE(frame.ok()) << text;
    EXPECT_EQ(frame.status().code(), StatusCode::kInvalidInput) << text;
  }
}

TEST(FindCameraIndexTest, FindsCamerasByExactName) {
  const Rig rig = TwoCameraRig();
  EXPECT_EQ(*FindCameraIndex("left", rig), 0);
  EXPECT_EQ(*FindCameraIndex("right", rig), 1);
}

TEST(FindCameraIndexTest, RejectsUnknownAndPathLikeNames) {
  const Rig rig = TwoCameraRig();
  for (const std::string name : {"", "Left", "center", "../left", "left/../right", "/etc/passwd",
                                 "..", "left/000000.png", "rig.yaml"}) {
    const StatusOr<int> camera = FindCameraIndex(name, rig);
    ASSERT_FALSE(camera.ok()) << name;
    EXPECT_EQ(camera.status().code(), StatusCode::kNotFound) << name;
    EXPECT_NE(camera.status().message().find("left, right"), std::string::npos);
  }
}

TEST(ResolveReviewTargetTest, ResolvesBothOrFails) {
  const Rig rig = TwoCameraRig();
  const StatusOr<ReviewTarget> target = ResolveReviewTarget("3", "right", 5, rig);
  ASSERT_TRUE(target.ok());
  EXPECT_EQ(target->frame, 3);
  EXPECT_EQ(target->camera, 1);
  EXPECT_FALSE(ResolveReviewTarget("3", "../right", 5, rig).ok());
  EXPECT_FALSE(ResolveReviewTarget("..", "right", 5, rig).ok());
}

}  // namespace
}  // namespace bcot
