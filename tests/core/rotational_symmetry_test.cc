#include "bcot/core/rotational_symmetry.h"

#include <gtest/gtest.h>

#include <random>

#include "bcot/core/se3.h"

namespace bcot {
namespace {

Eigen::Isometry3d RandomPose(std::mt19937* rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Vector6d twist;
  for (int i = 0; i < 6; ++i) twist[i] = normal(*rng);
  twist.head<3>() *= 100.0;
  return ExpSE3(twist);
}

RotationalSymmetry OffsetSymmetry() {
  return {Eigen::Vector3d(0.3, -0.5, 0.8).normalized(), Eigen::Vector3d(12.0, -4.0, 30.0)};
}

TEST(RotationalSymmetryTest, RotationKeepsTheAxisPointsFixed) {
  const RotationalSymmetry symmetry = OffsetSymmetry();
  const Eigen::Isometry3d s = symmetry.Rotation(1.1);
  for (double along : {-50.0, 0.0, 20.0}) {
    const Eigen::Vector3d on_axis = symmetry.point + along * symmetry.axis;
    EXPECT_LT((s * on_axis - on_axis).norm(), 1e-9);
  }
  EXPECT_NEAR(RotationDistanceDeg(s.linear(), Eigen::Matrix3d::Identity()), 1.1 * 180.0 / kPi,
              1e-9);
}

TEST(RotationalSymmetryTest, TwistGeneratesTheRotation) {
  const RotationalSymmetry symmetry = OffsetSymmetry();
  for (double angle : {-2.0, 0.3, 3.0}) {
    EXPECT_LT(
        (ExpSE3(angle * symmetry.Twist()).matrix() - symmetry.Rotation(angle).matrix()).norm(),
        1e-9);
  }
}

TEST(RotationalSymmetryTest, HoldAngleGivesAnEquivalentPoseNearestTheReference) {
  const RotationalSymmetry symmetry = OffsetSymmetry();
  std::mt19937 rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Isometry3d pose = RandomPose(&rng);
    const Eigen::Isometry3d reference = RandomPose(&rng);
    const Eigen::Isometry3d held = symmetry.HoldAngle(pose, reference);
    // Equivalent: the same map of every point on the axis, and a turn about the axis only.
    for (double along : {-40.0, 10.0}) {
      const Eigen::Vector3d on_axis = symmetry.point + along * symmetry.axis;
      EXPECT_LT((held * on_axis - pose * on_axis).norm(), 1e-9);
    }
    const Eigen::Vector3d turn = LogSO3(pose.linear().transpose() * held.linear());
    EXPECT_LT(turn.cross(symmetry.axis).norm(), 1e-9);
    // Nearest: no other angle about the axis brings the rotation closer to the reference.
    const double held_deg = RotationDistanceDeg(held.linear(), reference.linear());
    for (int k = 0; k < 360; ++k) {
      const Eigen::Isometry3d other = pose * symmetry.Rotation(k * kPi / 180.0);
      EXPECT_LE(held_deg, RotationDistanceDeg(other.linear(), reference.linear()) + 1e-9);
    }
    // Idempotent.
    EXPECT_NEAR(symmetry.NearestAngle(held, reference), 0.0, 1e-9);
  }
}

TEST(RotationalSymmetryTest, HoldAngleUndoesATurnAboutTheAxis) {
  const RotationalSymmetry symmetry = OffsetSymmetry();
  std::mt19937 rng(9);
  const Eigen::Isometry3d pose = RandomPose(&rng);
  const Eigen::Isometry3d turned = pose * symmetry.Rotation(2.5);
  const Eigen::Isometry3d held = symmetry.HoldAngle(turned, pose);
  EXPECT_LT((held.matrix() - pose.matrix()).norm(), 1e-9);
}

TEST(RotationalSymmetryTest, TransformedMapsAxisAndPoint) {
  const RotationalSymmetry symmetry = OffsetSymmetry();
  std::mt19937 rng(3);
  const Eigen::Isometry3d g_from_f = RandomPose(&rng);
  const RotationalSymmetry in_g = symmetry.Transformed(g_from_f);
  // S in G is g_from_f·S·f_from_g.
  const Eigen::Isometry3d expected = g_from_f * symmetry.Rotation(0.7) * g_from_f.inverse();
  EXPECT_LT((in_g.Rotation(0.7).matrix() - expected.matrix()).norm(), 1e-9);
}

}  // namespace
}  // namespace bcot
