// Shared checks of the costs with six residuals on one pose parameter block (pose damping,
// pose Gaussian): seeded test poses, ceres::GradientChecker, and the Jacobian in the manifold's
// tangent (ambient Jacobian · PlusJacobian) against central differences through
// Se3Manifold::Plus.
#pragma once

#include <ceres/cost_function.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bcot/core/se3.h"
#include "bcot/optim/se3_manifold.h"

namespace bcot::test {

// A pose turned by `angle` about a random axis, about 20 m in front of the origin.
inline Eigen::Isometry3d RandomPose(std::mt19937& rng, double angle) {
  std::normal_distribution<double> normal;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      ExpSO3(angle * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized());
  pose.translation() = Eigen::Vector3d(normal(rng), normal(rng), 500.0 + normal(rng)) * 40.0;
  return pose;
}

// `base` turned by `relative_angle` about a random axis (in its own frame) and moved by a random
// vector of about 5 mm per axis.
inline Eigen::Isometry3d TurnedAndMoved(const Eigen::Isometry3d& base, double relative_angle,
                                        std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::Isometry3d pose = base;
  pose.linear() =
      base.linear() *
      ExpSO3(relative_angle * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized());
  pose.translation() += Eigen::Vector3d(normal(rng), normal(rng), normal(rng)) * 5.0;
  return pose;
}

// ceres::GradientChecker with the Se3Manifold at `pose` (relative precision 1e-7).
inline void ExpectGradientCheckerAccepts(const ceres::CostFunction& cost,
                                         const Eigen::Isometry3d& pose,
                                         const std::string& context) {
  const Se3Manifold manifold;
  const std::vector<const ceres::Manifold*> manifolds = {&manifold};
  const ceres::NumericDiffOptions numeric_options;
  const ceres::GradientChecker checker(&cost, &manifolds, numeric_options);
  const PoseParameters x = ToPoseParameters(pose);
  const double* parameters[] = {x.data()};
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(parameters, 1e-7, &results)) << context << "\n" << results.error_log;
}

inline void ExpectTangentJacobianMatchesCentralDifferences(const ceres::CostFunction& cost,
                                                           const PoseParameters& x,
                                                           const std::string& context) {
  const Se3Manifold manifold;
  const double* parameters[] = {x.data()};
  Eigen::Matrix<double, 6, 7, Eigen::RowMajor> ambient;
  double* jacobians[] = {ambient.data()};
  double residuals[6];
  ASSERT_TRUE(cost.Evaluate(parameters, residuals, jacobians));
  Eigen::Matrix<double, 7, 6, Eigen::RowMajor> plus_jacobian;
  ASSERT_TRUE(manifold.PlusJacobian(x.data(), plus_jacobian.data()));
  const Eigen::Matrix<double, 6, 6> analytic = ambient * plus_jacobian;
  constexpr double kStep = 1e-6;
  for (int k = 0; k < 6; ++k) {
    double delta[6] = {0, 0, 0, 0, 0, 0};
    PoseParameters plus, minus;
    delta[k] = kStep;
    manifold.Plus(x.data(), delta, plus.data());
    delta[k] = -kStep;
    manifold.Plus(x.data(), delta, minus.data());
    double r_plus[6], r_minus[6];
    const double* p_plus[] = {plus.data()};
    const double* p_minus[] = {minus.data()};
    ASSERT_TRUE(cost.Evaluate(p_plus, r_plus, nullptr));
    ASSERT_TRUE(cost.Evaluate(p_minus, r_minus, nullptr));
    for (int i = 0; i < 6; ++i) {
      const double numeric = (r_plus[i] - r_minus[i]) / (2.0 * kStep);
      EXPECT_NEAR(analytic(i, k), numeric, 1e-6 * (1.0 + std::abs(numeric)))
          << context << " residual " << i << " tangent " << k;
    }
  }
}

}  // namespace bcot::test
