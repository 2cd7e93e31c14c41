#include "bcot/optim/pose_damping_cost.h"

#include <gtest/gtest.h>

#include <random>

#include "bcot/core/se3.h"
#include "bcot/optim/se3_manifold.h"
#include "pose_cost_checks.h"

namespace bcot {
namespace {

TEST(PoseDampingCostTest, IsZeroAtTheLinearisationPose) {
  std::mt19937 rng(3);
  const Eigen::Isometry3d pose = test::RandomPose(rng, 1.0);
  const PoseDampingCost cost(pose, 2.0, 30.0);
  PoseParameters x = ToPoseParameters(pose);
  const double* parameters[] = {x.data()};
  double residuals[6];
  ASSERT_TRUE(cost.Evaluate(parameters, residuals, nullptr));
  for (double r : residuals) EXPECT_NEAR(r, 0.0, 1e-12);
}

TEST(PoseDampingCostTest, MeasuresCentreDisplacementAndRotationAboutTheCentre) {
  std::mt19937 rng(5);
  const Eigen::Isometry3d pose_0 = test::RandomPose(rng, 2.0);
  // Move the centre by 3 mm along the object's x axis and rotate 0.1 rad about its z axis.
  Eigen::Isometry3d moved = pose_0;
  moved.translation() += pose_0.linear() * Eigen::Vector3d(3.0, 0.0, 0.0);
  moved.linear() = pose_0.linear() * ExpSO3(Eigen::Vector3d(0.0, 0.0, 0.1));
  const PoseDampingCost cost(pose_0, 2.0, 10.0);
  PoseParameters x = ToPoseParameters(moved);
  const double* parameters[] = {x.data()};
  double r[6];
  ASSERT_TRUE(cost.Evaluate(parameters, r, nullptr));
  EXPECT_NEAR(r[0], 6.0, 1e-9);
  EXPECT_NEAR(r[1], 0.0, 1e-9);
  EXPECT_NEAR(r[2], 0.0, 1e-9);
  EXPECT_NEAR(r[3], 0.0, 1e-9);
  EXPECT_NEAR(r[4], 0.0, 1e-9);
  EXPECT_NEAR(r[5], 1.0, 1e-9);
}

// Analytic Jacobian against ceres::GradientChecker, for relative rotations up to 2 rad. (Not at
// exactly T = T0: there the off-diagonal entries are exact zeros, which the checker's relative
// error compares with round-off noise. Beyond 2 rad the checker's ambient numeric derivative
// disagrees with central differences through Se3Manifold::Plus, which the next test uses.)
TEST(PoseDampingCostTest, GradientCheckerAcceptsTheJacobian) {
  std::mt19937 rng(7);
  for (double relative_angle : {1e-3, 0.3, 1.0, 2.0}) {
    const Eigen::Isometry3d pose_0 = test::RandomPose(rng, 1.5);
    const Eigen::Isometry3d pose = test::TurnedAndMoved(pose_0, relative_angle, rng);
    const PoseDampingCost cost(pose_0, 0.7, 12.0);
    test::ExpectGradientCheckerAccepts(cost, pose, "angle " + std::to_string(relative_angle));
  }
}

// Central differences of the residual through T ⊕ δ (what the solver steps along) against the
// Lie Jacobian, including relative rotations near π where Log is least well conditioned.
TEST(PoseDampingCostTest, LieJacobianMatchesCentralDifferencesThroughPlus) {
  std::mt19937 rng(11);
  for (double relative_angle : {1e-3, 1.0, 3.0, kPi - 1e-2}) {
    const Eigen::Isometry3d pose_0 = test::RandomPose(rng, 1.5);
    const Eigen::Isometry3d pose = test::TurnedAndMoved(pose_0, relative_angle, rng);
    const PoseDampingCost cost(pose_0, 0.7, 12.0);
    test::ExpectTangentJacobianMatchesCentralDifferences(cost, ToPoseParameters(pose),
                                                         "angle " + std::to_string(relative_angle));
  }
}

}  // namespace
}  // namespace bcot
