#include "bcot/optim/pose_gaussian_cost.h"

#include <gtest/gtest.h>

#include <random>

#include "bcot/core/se3.h"
#include "bcot/optim/se3_manifold.h"
#include "pose_cost_checks.h"

namespace bcot {
namespace {

// A random symmetric positive definite information matrix with a wide range of scales (1/mm² and
// 1/rad² entries as an edge fit gives them) and correlations between all six directions.
Matrix6d RandomInformation(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Matrix6d a;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) a(i, j) = normal(rng);
  }
  Vector6d scale;
  scale << 20.0, 30.0, 5.0, 2000.0, 3000.0, 1500.0;
  return scale.asDiagonal() * (a * a.transpose() + Matrix6d::Identity()) * scale.asDiagonal();
}

TEST(PoseGaussianCostTest, SqrtInformationFactorsTheMatrixAndRejectsSingularOnes) {
  std::mt19937 rng(2);
  const Matrix6d information = RandomInformation(rng);
  Matrix6d u;
  ASSERT_TRUE(SqrtInformation(information, &u));
  EXPECT_LT((u.transpose() * u - information).norm(), 1e-9 * information.norm());
  EXPECT_TRUE(u.isUpperTriangular());
  Matrix6d singular = information;
  singular.row(2).setZero();
  singular.col(2).setZero();
  EXPECT_FALSE(SqrtInformation(singular, &u));
}

// ½‖r‖² = ½ eᵀHe with e the centre displacement in the mean's object frame and the rotation.
TEST(PoseGaussianCostTest, ResidualIsTheWhitenedPoseError) {
  std::mt19937 rng(5);
  PoseGaussian gaussian;
  gaussian.mean = test::RandomPose(rng, 2.0);
  const Matrix6d information = RandomInformation(rng);
  ASSERT_TRUE(SqrtInformation(information, &gaussian.sqrt_information));
  const PoseGaussianCost cost(gaussian);
  PoseParameters x = ToPoseParameters(gaussian.mean);
  const double* at_mean[] = {x.data()};
  Vector6d r;
  ASSERT_TRUE(cost.Evaluate(at_mean, r.data(), nullptr));
  EXPECT_LT(r.norm(), 1e-9);
  // Move the centre by 0.3 mm along the object's x axis and rotate 0.01 rad about its z axis.
  Eigen::Isometry3d moved = gaussian.mean;
  moved.translation() += gaussian.mean.linear() * Eigen::Vector3d(0.3, 0.0, 0.0);
  moved.linear() = gaussian.mean.linear() * ExpSO3(Eigen::Vector3d(0.0, 0.0, 0.01));
  x = ToPoseParameters(moved);
  const double* at_moved[] = {x.data()};
  ASSERT_TRUE(cost.Evaluate(at_moved, r.data(), nullptr));
  Vector6d e;
  e << 0.3, 0.0, 0.0, 0.0, 0.0, 0.01;
  EXPECT_NEAR(r.squaredNorm(), e.dot(information * e), 1e-9 * e.dot(information * e));
}

// Analytic Jacobian against ceres::GradientChecker (not at exactly T = T̂, where entries that
// are exact zeros meet round-off in the checker's relative error).
TEST(PoseGaussianCostTest, GradientCheckerAcceptsTheJacobian) {
  std::mt19937 rng(7);
  for (double relative_angle : {1e-3, 0.3, 1.0, 2.0}) {
    PoseGaussian gaussian;
    gaussian.mean = test::RandomPose(rng, 1.5);
    ASSERT_TRUE(SqrtInformation(RandomInformation(rng) * 1e-4, &gaussian.sqrt_information));
    const Eigen::Isometry3d pose = test::TurnedAndMoved(gaussian.mean, relative_angle, rng);
    const PoseGaussianCost cost(gaussian);
    test::ExpectGradientCheckerAccepts(cost, pose, "angle " + std::to_string(relative_angle));
  }
}

// Central differences of the residual through T ⊕ δ against the Lie Jacobian, including
// relative rotations near π.
TEST(PoseGaussianCostTest, LieJacobianMatchesCentralDifferencesThroughPlus) {
  std::mt19937 rng(11);
  for (double relative_angle : {1e-3, 1.0, 3.0, kPi - 1e-2}) {
    PoseGaussian gaussian;
    gaussian.mean = test::RandomPose(rng, 1.5);
    ASSERT_TRUE(SqrtInformation(RandomInformation(rng) * 1e-4, &gaussian.sqrt_information));
    const Eigen::Isometry3d pose = test::TurnedAndMoved(gaussian.mean, relative_angle, rng);
    const PoseGaussianCost cost(gaussian);
    test::ExpectTangentJacobianMatchesCentralDifferences(cost, ToPoseParameters(pose),
                                                         "angle " + std::to_string(relative_angle));
  }
}

}  // namespace
}  // namespace bcot
