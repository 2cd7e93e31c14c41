// Checks the Jacobian a pose cost reports in the manifold's tangent (ambient Jacobian ·
// PlusJacobian) against central differences through Se3Manifold::Plus, for costs with six
// residuals on one pose parameter block (pose damping, pose Gaussian).
#pragma once

#include <ceres/cost_function.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bcot/optim/se3_manifold.h"

namespace bcot::test {

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
