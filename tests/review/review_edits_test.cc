// Pose edits of `bcot review`: the nudge moves the centre's projection by the requested pixels
// and rotates about the centre, the undo stack, and keyframes.txt written whole and merged.
#include "bcot/review/review_edits.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "bcot/core/file_util.h"
#include "bcot/core/keyframes.h"
#include "bcot/core/se3.h"
#include "test_util.h"

namespace bcot {
namespace {

using ::testing::HasSubstr;

RigCamera SideCamera() {
  // Looks along the rig's −x axis from x = 500 mm (rotation −90° about y), as cam1 of a 90° rig.
  RigCamera camera{Camera("side", 640, 480, 600, 610, 320, 240), Eigen::Isometry3d::Identity()};
  Eigen::Isometry3d rig_from_cam = Eigen::Isometry3d::Identity();
  rig_from_cam.linear() = ExpSO3(Eigen::Vector3d(0.0, -kPi / 2.0, 0.0));
  rig_from_cam.translation() = Eigen::Vector3d(500.0, 0.0, 600.0);
  camera.cam_from_rig = rig_from_cam.inverse();
  return camera;
}

Eigen::Isometry3d ObjectPose() {
  Eigen::Isometry3d rig_from_object = Eigen::Isometry3d::Identity();
  rig_from_object.linear() = ExpSO3(Eigen::Vector3d(0.3, -0.2, 0.5));
  rig_from_object.translation() = Eigen::Vector3d(20.0, -10.0, 610.0);
  return rig_from_object;
}

TEST(NudgePoseTest, MovesTheCentreByPixelsAndDepthAndRotatesAboutIt) {
  const RigCamera camera = SideCamera();
  const Eigen::Vector3d centre(5.0, -3.0, 8.0);
  const Eigen::Isometry3d pose = ObjectPose();
  const auto project = [&](const Eigen::Isometry3d& rig_from_object) {
    return camera.camera.Project(camera.cam_from_rig * rig_from_object * centre);
  };
  PoseNudge nudge;
  nudge.dx_px = 7.5;
  nudge.dy_px = -3.0;
  const StatusOr<Eigen::Isometry3d> moved = NudgePose(pose, centre, camera, nudge);
  ASSERT_TRUE(moved.ok()) << moved.status().message();
  EXPECT_TRUE((project(*moved) - project(pose)).isApprox(Eigen::Vector2d(7.5, -3.0), 1e-9));
  EXPECT_TRUE(moved->linear().isApprox(pose.linear(), 1e-12));

  nudge = PoseNudge();
  nudge.dz_mm = 12.0;
  const StatusOr<Eigen::Isometry3d> deeper = NudgePose(pose, centre, camera, nudge);
  ASSERT_TRUE(deeper.ok());
  const Eigen::Vector3d before = camera.cam_from_rig * pose * centre;
  const Eigen::Vector3d after = camera.cam_from_rig * *deeper * centre;
  EXPECT_NEAR(after.z() - before.z(), 12.0, 1e-9);
  EXPECT_NEAR(after.x(), before.x(), 1e-9);

  nudge = PoseNudge();
  nudge.rotation_deg = Eigen::Vector3d(0.0, 0.0, 10.0);  // about the viewing axis
  const StatusOr<Eigen::Isometry3d> turned = NudgePose(pose, centre, camera, nudge);
  ASSERT_TRUE(turned.ok());
  EXPECT_TRUE((project(*turned) - project(pose)).isZero(1e-9));  // the centre stays
  EXPECT_NEAR(RotationDistanceDeg(turned->linear(), pose.linear()), 10.0, 1e-9);
  // In the camera frame the change is a turn about the camera's z axis.
  const Eigen::Matrix3d change = (camera.cam_from_rig.linear() * turned->linear()) *
                                 (camera.cam_from_rig.linear() * pose.linear()).transpose();
  EXPECT_TRUE(LogSO3(change).isApprox(Eigen::Vector3d(0, 0, 10.0 * kPi / 180.0), 1e-9));
}

TEST(NudgePoseTest, CentreBehindTheCameraOrNonFiniteNudgeIsAnError) {
  const RigCamera camera = SideCamera();
  Eigen::Isometry3d behind = Eigen::Isometry3d::Identity();
  behind.translation() = Eigen::Vector3d(900.0, 0.0, 600.0);  // past the camera along its −z
  const StatusOr<Eigen::Isometry3d> result = NudgePose(behind, Eigen::Vector3d::Zero(), camera, {});
  ASSERT_FALSE(result.ok());
  EXPECT_THAT(result.status().message(), HasSubstr("not in front of side"));
  PoseNudge nudge;
  nudge.dx_px = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(NudgePose(ObjectPose(), Eigen::Vector3d::Zero(), camera, nudge).ok());
}

TEST(PoseEditsTest, UndoReturnsToThePreviousPose) {
  const Eigen::Isometry3d original = ObjectPose();
  PoseEdits edits({original, original});
  Eigen::Isometry3d first = original, second = original;
  first.translation().x() += 1.0;
  second.translation().x() += 2.0;
  edits.Push(1, first);
  edits.Push(1, second);
  EXPECT_EQ(edits.Depth(1), 2);
  EXPECT_TRUE(edits.Pose(1).isApprox(second));
  EXPECT_TRUE(edits.Pose(0).isApprox(original));
  EXPECT_TRUE(edits.Undo(1));
  EXPECT_TRUE(edits.Pose(1).isApprox(first));
  EXPECT_TRUE(edits.Undo(1));
  EXPECT_TRUE(edits.Pose(1).isApprox(original));
  EXPECT_FALSE(edits.Undo(1));
  EXPECT_FALSE(edits.Undo(0));
}

// A re-annotation of frames 1..2 replaces every original pose and drops the edits of those
// frames; the edit of frame 3 stays on top of its new original.
TEST(PoseEditsTest, RebaseDropsTheEditsOfTheReannotatedFrames) {
  const Eigen::Isometry3d original = ObjectPose();
  PoseEdits edits({original, original, original, original});
  Eigen::Isometry3d edited = original;
  edited.translation().y() += 3.0;
  for (int frame : {1, 2, 3}) edits.Push(frame, edited);
  Eigen::Isometry3d reannotated = original;
  reannotated.translation().z() += 1.0;
  edits.Rebase({reannotated, reannotated, reannotated, reannotated}, 1, 2);
  EXPECT_TRUE(edits.Pose(0).isApprox(reannotated));
  for (int frame : {1, 2}) {
    EXPECT_EQ(edits.Depth(frame), 0);
    EXPECT_TRUE(edits.Pose(frame).isApprox(reannotated));
  }
  EXPECT_EQ(edits.Depth(3), 1);
  EXPECT_TRUE(edits.Pose(3).isApprox(edited));
  EXPECT_TRUE(edits.Undo(3));
  EXPECT_TRUE(edits.Pose(3).isApprox(reannotated));
}

TEST(SetKeyframeTest, MergesWithTheFileAndReplacesTheFramesLine) {
  test::TempDir dir;
  const std::string path = dir.File("keyframes.txt");
  Eigen::Isometry3d a = ObjectPose(), b = ObjectPose();
  b.translation().y() += 5.0;
  ASSERT_TRUE(SetKeyframe(path, 7, a, 10).ok());
  ASSERT_TRUE(SetKeyframe(path, 2, a, 10).ok());
  ASSERT_TRUE(SetKeyframe(path, 7, b, 10).ok());
  const StatusOr<KeyframePoses> read = ReadKeyframeFile(path, 10);
  ASSERT_TRUE(read.ok()) << read.status().message();
  ASSERT_EQ(read->size(), 2u);
  EXPECT_TRUE(read->at(2).isApprox(a, 1e-12));
  EXPECT_TRUE(read->at(7).isApprox(b, 1e-12));
  EXPECT_EQ(ReadTextFile(path)->substr(0, 2), "2 ");  // frame order

  const Status outside = SetKeyframe(path, 10, a, 10);
  EXPECT_THAT(outside.message(), HasSubstr("keyframe 10: the sequence has frames 0..9"));
  test::WriteText(path, "3 not a pose\n");
  const Status broken = SetKeyframe(path, 1, a, 10);
  ASSERT_FALSE(broken.ok());
  EXPECT_THAT(broken.message(), HasSubstr(path));
  EXPECT_EQ(*ReadTextFile(path), "3 not a pose\n");  // left as it was
}

}  // namespace
}  // namespace bcot
